#include "transport/mlt/bootstrap.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "mc/rng.h"
#include "transport/mlt/startup_budget.h"
#include "render/distributed.h"
#include "transport/mlt/chain_ranks.h"

namespace ps {

uint64_t bootstrapSeed(uint64_t seed, int64_t i) { return mixWithKey(mix64(seed ^ 0x6a09e667f3bcc908ULL), uint64_t(i)); }

namespace {

// The share of the defaults in what the pilot learns: large enough that a strategy or a
// group the pilot missed is still proposed and sampled now and then, small enough to leave
// most of both to those that carry the image.
constexpr double kDefaultShare = 0.25;

// What a run of independent samples gives: each sample's total weight and, when learning,
// each strategy's summed weight and each group's sum and sum of squares of its samples'
// target totals (weights over the group's scale).
struct Samples {
    std::vector<double> weight, parts, groupSum, groupSumSquares;
};

// Sample j of a run from `first` on, stratified within its group: b is the image mean
// (PrimarySampleSampler::stratifyFirstIteration; docs/integrators.md, "The bootstrap").
void stratify(const BootstrapContext& ctx, PrimarySampleSampler& sampler, int64_t first, const BootstrapAllocation& alloc,
              int g, int64_t j) {
    sampler.stratifyFirstIteration(hashCombine(hashCombine(ctx.seed ^ 0x3c6ef372fe94f82bULL, uint64_t(first)), uint64_t(g)),
                                   j - alloc.start[size_t(g)], alloc.count[size_t(g)]);
}

// Samples first .. first + alloc.total - 1. Blocks of samples are summed in order, so the
// sums do not depend on the thread count; over several processes each takes its blocks
// (chain_ranks.h) and every process gets all the weights and block sums, bit for bit.
Samples sampleIndependently(const BootstrapContext& ctx, int64_t first, const BootstrapAllocation& alloc,
                            const StrategyChoice& choice, bool learn, std::atomic<bool>& cancelled) {
    constexpr int64_t kBlock = 1024;
    const int64_t count = alloc.total, blocks = (count + kBlock - 1) / kBlock;
    const size_t strategies = size_t(choice.size()), groups = alloc.count.size();
    // A block's sums: the strategies its samples can reach, then each group's sum and sum of
    // squares. The groups are contiguous runs of samples and, where the choice has a group
    // per bootstrap group (mmlt: a depth), a block reaches only its groups' strategies: a
    // dense row over every strategy per block took (maxdepth^2 / 2) x blocks doubles, 39 GB
    // at maxdepth 1000.
    const bool perGroup = int(groups) == choice.groups();
    std::vector<size_t> rowStart(size_t(blocks) + 1, 0);
    std::vector<int> firstStrategy(size_t(blocks), 0);
    for (int64_t block = 0; learn && block < blocks; ++block) {
        const int g0 = alloc.groupOf(block * kBlock), g1 = alloc.groupOf(std::min(count, (block + 1) * kBlock) - 1);
        const int lo = perGroup ? choice.groupBegin(g0) : 0;
        const int hi = perGroup ? choice.groupBegin(g1 + 1) : int(strategies);
        firstStrategy[size_t(block)] = lo;
        rowStart[size_t(block) + 1] = rowStart[size_t(block)] + size_t(hi - lo) + 2 * groups;
    }
    std::vector<double> blockSums(learn ? rowStart.back() : 0, 0.0);
    Samples out;
    out.weight.assign(size_t(count), 0.0);
    tbb::enumerable_thread_specific<std::vector<BootstrapState>> found;
    ctx.arena.execute([&] {
        tbb::parallel_for(int64_t(0), blocks, [&](int64_t block) {
            if (!chain_ranks::ownsBlock(block)) return;
            if (ctx.cancel && ctx.cancel->load()) cancelled = true;
            if (cancelled.load(std::memory_order_relaxed)) return;
            std::vector<BootstrapState>& states = found.local();
            double* sums = learn ? &blockSums[rowStart[size_t(block)]] : nullptr;
            const int lo = firstStrategy[size_t(block)];
            const size_t reach = learn ? rowStart[size_t(block) + 1] - rowStart[size_t(block)] - 2 * groups : 0;
            double* groupSums = sums ? sums + reach : nullptr;
            for (int64_t j = block * kBlock; j < std::min(count, (block + 1) * kBlock); ++j) {
                const int g = alloc.groupOf(j);
                PrimarySampleSampler sampler(bootstrapSeed(ctx.seed, first + j), ctx.pss);
                sampler.startIteration();
                stratify(ctx, sampler, first, alloc, g, j);
                ctx.integrator.bootstrapSample(sampler, g, alloc.scale(g), choice, ctx.evaluators.local(), states);
                double w = 0;
                for (const BootstrapState& st : states) {
                    w += st.weight;
                    if (sums && st.strategy >= lo && size_t(st.strategy - lo) < reach) sums[st.strategy - lo] += st.weight;
                }
                out.weight[size_t(j)] = w;
                if (groupSums) {
                    const double v = w / alloc.scale(g);
                    groupSums[size_t(g)] += v;
                    groupSums[groups + size_t(g)] += v * v;
                }
            }
            if (ctx.progress) ctx.progress->fetch_add(std::min(count, (block + 1) * kBlock) - block * kBlock,
                                                      std::memory_order_relaxed);
        });
    });
    {
        distributed::Purpose purpose("bootstrap merge");
        distributed::mergeDisjoint(out.weight);
        distributed::mergeDisjoint(blockSums);
        cancelled = distributed::anyOf(cancelled.load());
    }
    if (learn) {
        out.parts.assign(strategies, 0.0);
        out.groupSum.assign(groups, 0.0);
        out.groupSumSquares.assign(groups, 0.0);
        for (int64_t block = 0; block < blocks; ++block) {
            const double* row = &blockSums[rowStart[size_t(block)]];
            const size_t reach = rowStart[size_t(block) + 1] - rowStart[size_t(block)] - 2 * groups;
            for (size_t k = 0; k < reach; ++k) out.parts[size_t(firstStrategy[size_t(block)]) + k] += row[k];
            for (size_t g = 0; g < groups; ++g) {
                out.groupSum[g] += row[reach + g];
                out.groupSumSquares[g] += row[reach + groups + g];
            }
        }
    }
    return out;
}

// Each strategy's part of b, mixed with the default choice.
StrategyChoice learnedChoice(const StrategyChoice& defaults, const std::vector<double>& parts) {
    double total = 0, defaultTotal = 0;
    for (double p : parts) total += p;
    for (float w : defaults.weights()) defaultTotal += w;
    if (!(total > 0) || !(defaultTotal > 0)) return defaults;
    std::vector<float> learned(parts.size());
    for (size_t k = 0; k < parts.size(); ++k)
        learned[k] = float((1 - kDefaultShare) * parts[k] / total + kDefaultShare * defaults.weights()[k] / defaultTotal);
    return defaults.withWeights(learned);
}

// Neyman allocation from the pilot's spread per group, mixed with an allocation that
// assumes every group spreads alike.
std::vector<double> groupShares(const MetropolisIntegrator& integrator, const Samples& pilot,
                                const BootstrapAllocation& pilotGroups) {
    const size_t groups = pilotGroups.count.size();
    std::vector<double> neyman(groups), defensive(groups);
    double sumNeyman = 0, sumDefensive = 0;
    for (size_t g = 0; g < groups; ++g) {
        const double n = double(pilotGroups.count[g]), mean = pilot.groupSum[g] / n;
        const double sigma = std::sqrt(std::max(0.0, pilot.groupSumSquares[g] / n - mean * mean));
        const double rootCost = std::sqrt(std::max(1e-6, integrator.groupCost(int(g))));
        sumNeyman += (neyman[g] = sigma / rootCost);
        sumDefensive += (defensive[g] = 1 / rootCost);
    }
    std::vector<double> share(groups);
    for (size_t g = 0; g < groups; ++g)
        share[g] = sumNeyman > 0 ? (1 - kDefaultShare) * neyman[g] / sumNeyman + kDefaultShare * defensive[g] / sumDefensive
                                 : defensive[g] / sumDefensive;
    return share;
}

}  // namespace

BootstrapAllocation BootstrapAllocation::even(int64_t total, int groups) {
    BootstrapAllocation a;
    a.total = total;
    for (int g = 0; g < groups; ++g) {
        a.start.push_back(g == 0 ? 0 : a.start.back() + a.count.back());
        a.count.push_back(total / groups + (g < total % groups ? 1 : 0));
    }
    return a;
}

BootstrapAllocation BootstrapAllocation::proportional(int64_t total, const std::vector<double>& share) {
    BootstrapAllocation a;
    for (size_t g = 0; g < share.size(); ++g) {
        a.start.push_back(a.total);
        a.count.push_back(std::max<int64_t>(1, int64_t(share[g] * double(total))));
        a.total += a.count.back();
    }
    return a;
}

int BootstrapAllocation::groupOf(int64_t j) const {
    return int(std::upper_bound(start.begin(), start.end(), j) - start.begin()) - 1;
}

int64_t bootstrapIndexCount(const MetropolisIntegrator& integrator) {
    return std::max<int64_t>(std::max(1, integrator.bootstrapGroups()), integrator.bootstrapCount());
}

void probeBootstrap(const BootstrapContext& ctx, int64_t count) {
    // Evaluators of its own, so that its rays are not counted as the render's (the pilot
    // image, not yet made, would divide by 1 anyway).
    tbb::enumerable_thread_specific<ChainEvaluator> evaluators;
    const BootstrapContext probe{ctx.integrator, ctx.pss,       startupProbeSeed(ctx.seed),
                                 ctx.cancel,     ctx.arena,     evaluators,
                                 nullptr};
    std::atomic<bool> cancelled{false};
    const int groups = std::max(1, ctx.integrator.bootstrapGroups());
    sampleIndependently(probe, 0, BootstrapAllocation::even(std::max<int64_t>(count, groups), groups),
                        ctx.integrator.defaultChoice(), false, cancelled);
}

Bootstrap runBootstrap(const BootstrapContext& ctx, int64_t samples) {
    const MetropolisIntegrator& integrator = ctx.integrator;
    const MetropolisParams& mp = integrator.params();
    const int groups = std::max(1, integrator.bootstrapGroups());
    const int64_t nAll = std::max<int64_t>(groups, samples);
    Bootstrap boot;
    boot.choice = integrator.defaultChoice();
    std::atomic<bool> cancelled{false};
    // The pilot: every group equally often.
    const int64_t pilotPerGroup = int64_t(double(nAll / groups) * mp.strategyPilot);
    const bool pilot = (!boot.choice.empty() || groups > 1) && pilotPerGroup > 0 && pilotPerGroup * groups < nAll;
    int64_t nBoot = nAll;
    boot.groups = BootstrapAllocation::even(nAll, groups);
    if (pilot) {
        const BootstrapAllocation pilotGroups = BootstrapAllocation::even(pilotPerGroup * groups, groups);
        const Samples s = sampleIndependently(ctx, 0, pilotGroups, boot.choice, true, cancelled);
        if (!boot.choice.empty()) boot.choice = learnedChoice(boot.choice, s.parts);
        boot.pilotSamples = boot.first = pilotGroups.total;
        nBoot = nAll - pilotGroups.total;
        boot.groups = groups > 1 ? BootstrapAllocation::proportional(nBoot, groupShares(integrator, s, pilotGroups))
                                 : BootstrapAllocation::even(nBoot, 1);
    }
    boot.weights = sampleIndependently(ctx, boot.first, boot.groups, boot.choice, false, cancelled).weight;
    boot.cancelled = cancelled.load();
    boot.cumulative.resize(boot.weights.size());
    for (size_t i = 0; i < boot.weights.size(); ++i) boot.cumulative[i] = (boot.sum += boot.weights[i]);
    const double n = double(boot.weights.size());
    boot.b = boot.sum / n;
    // b scales the whole image: its own error, which the chains' half-buffers cannot see;
    // the groups are strata, each with its own spread.
    double variance = 0;
    for (size_t g = 0; g < boot.groups.count.size(); ++g) {
        const int64_t begin = boot.groups.start[g], m = boot.groups.count[g];
        double mean = 0, squares = 0;
        for (int64_t i = begin; i < begin + m; ++i) {
            mean += boot.weights[size_t(i)] / double(m);
            squares += boot.weights[size_t(i)] * boot.weights[size_t(i)] / double(m);
        }
        variance += double(m) * std::max(0.0, squares - mean * mean) / (n * n);
    }
    boot.bRelativeError = boot.b > 0 ? std::sqrt(variance) / boot.b : 0.0;
    return boot;
}

void runImportancePilot(const BootstrapContext& ctx, int64_t first, int64_t count, PilotImportance& importance) {
    tbb::enumerable_thread_specific<std::vector<BDPTIntegrator::PathContribution>> splats;
    importance.learn(ctx.arena, count, [&](int64_t j, double* sums) {
        std::vector<BDPTIntegrator::PathContribution>& x = splats.local();
        PrimarySampleSampler sampler(bootstrapSeed(ctx.seed, first + j), ctx.pss);
        sampler.startIteration();
        ctx.integrator.bdptSample(sampler, ctx.evaluators.local(), x);
        for (const BDPTIntegrator::PathContribution& c : x)
            if (const double y = c.L.luminance(); std::isfinite(y)) sums[importance.tileOf(c.pRaster)] += y;
        if (ctx.progress) ctx.progress->fetch_add(1, std::memory_order_relaxed);
    }, ctx.cancel);
}

bool startChain(const BootstrapContext& ctx, const Bootstrap& boot, Rng& rng,
                std::unique_ptr<PrimarySampleSampler>& sampler, ChainState& x) {
    // A bootstrap sample in proportion to its total weight, then one of its states.
    const int64_t n = int64_t(boot.weights.size());
    double pick = rng.uniformDouble() * boot.sum;
    int64_t i = std::upper_bound(boot.cumulative.begin(), boot.cumulative.end(), pick) - boot.cumulative.begin();
    i = std::min<int64_t>(i, n - 1);
    while (i > 0 && boot.weights[size_t(i)] == 0) --i;  // a rounding at the end: the last positive one
    const int g = boot.groups.groupOf(i);
    sampler = std::make_unique<PrimarySampleSampler>(bootstrapSeed(ctx.seed, boot.first + i), ctx.pss);
    sampler->startIteration();
    stratify(ctx, *sampler, boot.first, boot.groups, g, i);
    ChainEvaluator& ev = ctx.evaluators.local();
    std::vector<BootstrapState> found;
    ctx.integrator.bootstrapSample(*sampler, g, boot.groups.scale(g), boot.choice, ev, found);
    double w = 0;
    for (const BootstrapState& st : found) w += st.weight;
    if (w != boot.weights[size_t(i)] || found.empty()) return false;
    pick = rng.uniformDouble() * w;
    size_t j = 0;
    for (double below = found[0].weight; j + 1 < found.size() && below <= pick;) below += found[++j].weight;
    // The state alone, in the same proposal: its values are the ones just read.
    sampler->restartStreams();
    const double u1 = rng.uniformDouble();
    ctx.integrator.chooseStrategy(*sampler, found[j].strategy, boot.choice, u1, rng.uniformDouble());
    ctx.integrator.evaluate(*sampler, boot.choice, ev, x);
    sampler->accept();
    // The state's own evaluation may take another code path than the bootstrap's
    // (multiplexed MLT: one strategy's subpaths, not a depth's), which the compiler may
    // round differently (fused multiply-adds): equal to 1e-5.
    return std::abs(x.f - found[j].f) <= 1e-5 * found[j].f;
}

}  // namespace ps
