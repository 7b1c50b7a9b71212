#include "transport/mlt/metropolis.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "mc/estimator.h"
#include "mc/primary_sample_sampler.h"
#include "transport/render_monitor.h"
#include "util/error.h"

namespace ps {

MetropolisIntegrator::MetropolisIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params,
                                           MisHeuristic heuristic)
    : scene_(scene), bdpt_(scene, maxDepth, heuristic), params_(params) {
    const Camera::Params& c = scene.camera().params();
    margin_ = scene.filter().radius();
    filmSize_ = Vec2(float(c.xRes) + 2 * margin_.x, float(c.yRes) + 2 * margin_.y);
}

Spectrum MetropolisIntegrator::Li(const Ray&, SampleContext&) const {
    throw std::logic_error(std::string(name()) + " is a Markov-chain integrator: render it with renderMetropolis");
}

CameraSample MetropolisIntegrator::filmSample(PrimarySampleSampler& sampler) const {
    sampler.startStream(BDPTIntegrator::kCameraStream);
    Vec2 u = sampler.get2D();
    CameraSample cs;
    cs.pFilm = {-margin_.x + u.x * filmSize_.x, -margin_.y + u.y * filmSize_.y};
    cs.pLens = sampler.get2D();
    if (!(scene_.camera().params().lensRadius > 0)) cs.pLens = Vec2(0.5f, 0.5f);
    return cs;
}

namespace {

using PathContribution = BDPTIntegrator::PathContribution;

// Keys of the random streams, per bootstrap sample and per chain. The seed is mixed before
// the index enters: keyed on seed ^ constant directly, nearby seeds would give largely the
// same set of keys over a range of indices (shifted), and renders with different seeds would
// share most of their bootstrap samples.
uint64_t bootstrapSeed(uint64_t seed, int64_t i) { return mixWithKey(mix64(seed ^ 0x6a09e667f3bcc908ULL), uint64_t(i)); }
uint64_t chainSeed(uint64_t seed, int chain) { return mixWithKey(mix64(seed ^ 0xbb67ae8584caa73bULL), uint64_t(chain)); }

// The share of the default in a learned strategy choice: large enough that a strategy the
// pilot missed is still proposed now and then, small enough to leave most proposals to the
// strategies that carry the image.
constexpr double kDefaultChoiceShare = 0.25;

struct ChainCounts {
    long long proposedLarge = 0, acceptedLarge = 0, proposedSmall = 0, acceptedSmall = 0, invalid = 0, done = 0;
    // Per path depth: proposals and acceptances (by the proposal's depth, when the chain
    // chooses it), and the expected-value weight of each depth's splats in units of the
    // target (their sum over depths is the number of iterations).
    std::vector<long long> proposedAt, acceptedAt;
    std::vector<double> shareAt;
};

// A chain between passes: its sampler (the state's primary sample), the state, its own
// acceptance stream and the mutations it has left.
struct Chain {
    std::unique_ptr<PrimarySampleSampler> sampler;
    ChainState x;
    Rng rng;
    long long remaining = 0;
};

// The expected-value weight w of sample x, splatted (divided by its target value) onto the
// film and, if recorded, each depth's film; its share of the target goes to its depths.
void record(const ChainState& x, double w, int chain, Film& film, std::vector<std::unique_ptr<Film>>& depthFilms,
            ChainCounts& cc) {
    const float scale = float(w / x.f);
    for (const PathContribution& pc : x.splats) {
        const Spectrum L = pc.L * scale;
        film.addSplat(pc.pRaster, L, chain);
        const size_t depth = size_t(pc.s + pc.t - 2);
        if (depth < cc.shareAt.size()) cc.shareAt[depth] += w * pc.L.luminance() / x.f;
        if (depth < depthFilms.size()) depthFilms[depth]->addSplat(pc.pRaster, L, chain);
    }
}

}  // namespace

void MetropolisIntegrator::bootstrapSample(PrimarySampleSampler& sampler, int64_t, const StrategyChoice& choice,
                                           ChainEvaluator& ev, std::vector<BootstrapState>& out) const {
    out.clear();
    evaluate(sampler, choice, ev, ev.sample);
    if (ev.sample.f > 0) out.push_back({ev.sample.strategy, ev.sample.f, ev.sample.f});
}

RenderResult renderMetropolis(const Scene& scene, const MetropolisIntegrator& integrator, const RenderOptions& options) {
    const std::string name = integrator.name();
    if (!scene.camera().hasImportance())
        throw InputError("integrator \"" + name + "\" splats every path onto the film and needs a perspective camera");
    if (std::isfinite(scene.settings().maxComponentValue))
        warning(name + ": Film \"maxcomponentvalue\" is not applied to Metropolis renders (a chain's splats are "
                       "not camera samples); the image is not clamped");
    const MetropolisParams& mp = integrator.params();
    const PixelBounds& bounds = scene.pixelBounds();
    const Camera::Params& cp = scene.camera().params();
    Film film(cp.xRes, cp.yRes, bounds, &scene.filter());
    const int depths = integrator.maxDepth() + 1;
    std::vector<std::unique_ptr<Film>> depthFilms;
    if (mp.depthImages)
        for (int d = 0; d < depths; ++d) depthFilms.push_back(std::make_unique<Film>(cp.xRes, cp.yRes, bounds, &scene.filter()));
    PrimarySampleParams pss;
    pss.sigma = mp.sigma;
    pss.largeStepProbability = mp.largeStepProbability;
    pss.streamCount = integrator.streamCount();

    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    tbb::enumerable_thread_specific<ChainEvaluator> evaluators;
    tbb::enumerable_thread_specific<ChainState> proposals;

    RenderResult result;
    MetropolisStats& ms = result.metropolis;
    ms.present = true;
    ms.multiplexed = integrator.choosesDepth();

    // Bootstrap: b and the weights of the candidate initial states. It counts against the
    // time budget, and a cancellation during it leaves a black image (b unknown).
    const auto startTime = std::chrono::steady_clock::now();
    std::atomic<bool> bootstrapCancelled{false};
    // Independent samples first .. first + count - 1: each one's total weight and, if
    // `parts` is given, the sum of the weights of each strategy. Blocks of samples are summed
    // in order, so the sums do not depend on the thread count.
    auto sampleIndependently = [&](int64_t first, int64_t count, const StrategyChoice& choice,
                                   std::vector<double>& weight, std::vector<double>* parts) {
        constexpr int64_t kBlock = 1024;
        const int64_t blocks = (count + kBlock - 1) / kBlock;
        const size_t strategies = size_t(choice.size());
        std::vector<double> blockParts(parts ? size_t(blocks) * strategies : 0, 0.0);
        weight.assign(size_t(count), 0.0);
        tbb::enumerable_thread_specific<std::vector<BootstrapState>> found;
        arena.execute([&] {
            tbb::parallel_for(int64_t(0), blocks, [&](int64_t block) {
                if (options.cancel && options.cancel->load()) bootstrapCancelled = true;
                if (bootstrapCancelled.load(std::memory_order_relaxed)) return;
                std::vector<BootstrapState>& out = found.local();
                for (int64_t j = block * kBlock; j < std::min(count, (block + 1) * kBlock); ++j) {
                    PrimarySampleSampler sampler(bootstrapSeed(options.seed, first + j), pss);
                    sampler.startIteration();
                    integrator.bootstrapSample(sampler, first + j, choice, evaluators.local(), out);
                    double w = 0;
                    for (const BootstrapState& st : out) {
                        w += st.weight;
                        if (parts && st.strategy >= 0 && size_t(st.strategy) < strategies)
                            blockParts[size_t(block) * strategies + size_t(st.strategy)] += st.weight;
                    }
                    weight[size_t(j)] = w;
                }
            });
        });
        if (parts) {
            parts->assign(strategies, 0.0);
            for (int64_t block = 0; block < blocks; ++block)
                for (size_t k = 0; k < strategies; ++k) (*parts)[k] += blockParts[size_t(block) * strategies + k];
        }
    };
    // A target that chooses among strategies first learns how often to choose each: a
    // pilot estimates each strategy's part of b, and the choice becomes those parts mixed
    // with the default (so that no strategy's probability is 0: every path the target can
    // reach stays reachable by a large step). The pilot's samples are used for nothing else,
    // so the choice does not depend on the bootstrap proper, from which b and the initial
    // states come, and the argument against start-up bias holds as it is.
    StrategyChoice choice = integrator.defaultChoice();
    const std::vector<float> defaultWeights = choice.weights();
    const int64_t nAll = std::max<int64_t>(1, integrator.bootstrapCount());
    int64_t nPilot = 0;
    if (!defaultWeights.empty() && mp.strategyPilot > 0) {
        // Whole rounds of the depths (bootstrap sample i has depth i mod depths), so that
        // the bootstrap proper keeps whole rounds too.
        const int64_t perDepth = nAll / depths, pilotPerDepth = int64_t(double(perDepth) * mp.strategyPilot);
        if (nAll % depths == 0 && pilotPerDepth > 0 && pilotPerDepth < perDepth) nPilot = pilotPerDepth * depths;
    }
    std::vector<double> weights;
    if (nPilot > 0) {
        std::vector<double> parts;
        sampleIndependently(0, nPilot, choice, weights, &parts);
        double total = 0, defaultTotal = 0;
        for (double p : parts) total += p;
        for (float w : defaultWeights) defaultTotal += w;
        if (total > 0) {
            std::vector<float> learned(parts.size());
            for (size_t k = 0; k < parts.size(); ++k)
                learned[k] = float((1 - kDefaultChoiceShare) * parts[k] / total +
                                   kDefaultChoiceShare * defaultWeights[k] / defaultTotal);
            choice = choice.withWeights(learned);
        }
    }
    const int64_t nBoot = nAll - nPilot;
    sampleIndependently(nPilot, nBoot, choice, weights, nullptr);
    std::vector<double> cumulative(weights.size());
    double sum = 0, sumSquares = 0;
    for (size_t i = 0; i < weights.size(); ++i) {
        cumulative[i] = (sum += weights[i]);
        sumSquares += weights[i] * weights[i];
    }
    ms.bootstrapSamples = nBoot;
    ms.pilotSamples = nPilot;
    ms.depths.assign(size_t(depths), {});
    for (int k = 0; k < choice.size(); ++k)
        if (const int d = choice.groupOf(k); d < depths) ms.depths[size_t(d)].chosen += choice.pmf(k);
    ms.b = sum / double(nBoot);
    // b scales the whole image: its own error, which the chains' half-buffers cannot see.
    const double varianceB = std::max(0.0, sumSquares / double(nBoot) - ms.b * ms.b) / double(nBoot);
    ms.bRelativeError = ms.b > 0 ? std::sqrt(varianceB) / ms.b : 0.0;

    const long long total = std::max(1LL, (long long)std::max(1, options.spp) * bounds.area());
    const int chains = int(std::min<long long>(std::max(1, mp.chains), total));
    ms.chains = chains;
    std::atomic<bool> stop{false};
    std::atomic<long long> done{0};
    std::vector<ChainCounts> counts(static_cast<size_t>(chains));
    bool replayFailed = false;
    const double bootstrapSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();
    result.seconds = bootstrapSeconds;
    if (bootstrapCancelled) {
        warning(name + ": interrupted during the bootstrap, before any chain ran; the image is black");
        ms.b = 0;
    } else if (!(ms.b > 0)) {
        warning(name + ": the " + std::to_string(nBoot) +
                " bootstrap samples found no path that carries light to the camera; the image is black");
    } else {
        // The chains get what the bootstrap left of the budget, and at least a tenth of it.
        double chainTime = options.timeLimit;
        if (chainTime > 0) {
            chainTime = std::max(options.timeLimit - bootstrapSeconds, 0.1 * options.timeLimit);
            if (bootstrapSeconds > 0.9 * options.timeLimit)
                warning(name + ": the bootstrap took " + std::to_string(bootstrapSeconds) + " s of the " +
                        std::to_string(options.timeLimit) + " s budget; fewer bootstrap samples leave the chains more");
        }
        Monitor monitor(options.progress, chainTime, options.cancel, stop, done, total);
        std::atomic<bool> replayMismatch{false};
        // Every chain starts from a bootstrap state, then all advance in passes of a few
        // hundred mutations each, so that a render stopped early (time budget, Ctrl-C) has
        // mutations from every chain, not the whole of a few.
        std::vector<Chain> all(static_cast<size_t>(chains));
        arena.execute([&] {
            tbb::parallel_for(0, chains, [&](int c) {
                Chain& ch = all[size_t(c)];
                ChainCounts& cc = counts[size_t(c)];
                cc.proposedAt.assign(size_t(depths), 0);
                cc.acceptedAt.assign(size_t(depths), 0);
                cc.shareAt.assign(size_t(depths), 0.0);
                ch.rng = Rng(chainSeed(options.seed, c), 0x3c6ef372fe94f82bULL);
                // The initial state in proportion to its bootstrap weight: a bootstrap sample
                // in proportion to its total, then one of its states, replayed.
                double pick = ch.rng.uniformDouble() * sum;
                int64_t i = std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin();
                i = std::min<int64_t>(i, nBoot - 1);
                while (i > 0 && weights[size_t(i)] == 0) --i;  // a rounding at the end: the last positive one
                ch.sampler = std::make_unique<PrimarySampleSampler>(bootstrapSeed(options.seed, nPilot + i), pss);
                ch.sampler->startIteration();
                ChainEvaluator& ev = evaluators.local();
                std::vector<BootstrapState> found;
                integrator.bootstrapSample(*ch.sampler, nPilot + i, choice, ev, found);
                double w = 0;
                for (const BootstrapState& st : found) w += st.weight;
                pick = ch.rng.uniformDouble() * w;
                size_t j = 0;
                for (double below = found.empty() ? 0 : found[0].weight; j + 1 < found.size() && below <= pick;)
                    below += found[++j].weight;
                if (w != weights[size_t(i)] || found.empty()) {
                    replayMismatch = true;
                    return;
                }
                ch.sampler->restartStreams();
                const double u1 = ch.rng.uniformDouble();
                integrator.chooseStrategy(*ch.sampler, found[j].strategy, choice, u1, ch.rng.uniformDouble());
                integrator.evaluate(*ch.sampler, choice, ev, ch.x);
                ch.sampler->accept();
                // The state's own evaluation may take another code path than the bootstrap's
                // (multiplexed MLT: one strategy's subpaths, not a depth's), which the
                // compiler may round differently (fused multiply-adds): equal to 1e-5.
                if (!(std::abs(ch.x.f - found[j].f) <= 1e-5 * found[j].f)) replayMismatch = true;
                ch.sampler->reseed(chainSeed(options.seed, c));
                ch.remaining = total / chains + (c < total % chains ? 1 : 0);
            });
        });
        constexpr long long kPass = 256;
        const long long largestShare = total / chains + (total % chains ? 1 : 0);
        for (long long pass = 0; pass * kPass < largestShare && !replayMismatch && !stop.load(); ++pass) {
            arena.execute([&] {
                tbb::parallel_for(0, chains, [&](int c) {
                    if (stop.load(std::memory_order_relaxed)) return;
                    Chain& ch = all[size_t(c)];
                    const long long n = std::min(ch.remaining, kPass);
                    ChainEvaluator& ev = evaluators.local();
                    ChainState& y = proposals.local();
                    ChainCounts& cc = counts[size_t(c)];
                    PrimarySampleSampler& sampler = *ch.sampler;
                    for (long long k = 0; k < n; ++k) {
                        sampler.startIteration();
                        const bool large = sampler.largeStep();
                        integrator.evaluate(sampler, choice, ev, y);
                        const double a = acceptanceProbability(ch.x.f, y.f);
                        if (!(y.f > 0)) ++cc.invalid;
                        // Expected values: the state with 1 - a, the proposal with a.
                        if (a < 1) record(ch.x, 1 - a, c, film, depthFilms, cc);
                        if (a > 0) record(y, a, c, film, depthFilms, cc);
                        ++(large ? cc.proposedLarge : cc.proposedSmall);
                        if (y.depth >= 0) ++cc.proposedAt[size_t(y.depth)];
                        if (ch.rng.uniformDouble() < a) {
                            sampler.accept();
                            std::swap(ch.x, y);
                            ++(large ? cc.acceptedLarge : cc.acceptedSmall);
                            if (ch.x.depth >= 0) ++cc.acceptedAt[size_t(ch.x.depth)];
                        } else {
                            sampler.reject();
                        }
                    }
                    ch.remaining -= n;
                    cc.done += n;
                    done.fetch_add(n, std::memory_order_relaxed);
                });
            });
        }
        result.seconds += monitor.elapsed();
        replayFailed = replayMismatch.load();
    }
    if (replayFailed)
        throw std::logic_error(name + ": a bootstrap sample replayed with a different contribution");

    for (const ChainCounts& cc : counts) {
        ms.proposedLarge += cc.proposedLarge;
        ms.acceptedLarge += cc.acceptedLarge;
        ms.proposedSmall += cc.proposedSmall;
        ms.acceptedSmall += cc.acceptedSmall;
        ms.invalidProposals += cc.invalid;
        ms.mutations += cc.done;
        for (size_t d = 0; d < cc.shareAt.size(); ++d) {
            ms.depths[d].proposed += cc.proposedAt[d];
            ms.depths[d].accepted += cc.acceptedAt[d];
            ms.depths[d].share += cc.shareAt[d];
        }
    }
    for (MetropolisStats::Depth& d : ms.depths) d.share = ms.mutations > 0 ? d.share / double(ms.mutations) : 0.0;
    for (const ChainEvaluator& ev : evaluators) result.stats += ev.stats;
    // Splats are normalised by "light paths" (Film::image): mutations / b per unit of the
    // target's integral, with the imaging ratio as for BDPT's splats.
    const float imagingRatio = scene.settings().imagingRatio;
    const double lightPaths =
        ms.b > 0 && imagingRatio > 0 && ms.mutations > 0 ? double(ms.mutations) / (ms.b * imagingRatio) : 0.0;
    result.targetSpp = std::max(1, options.spp);
    result.meanSpp = double(ms.mutations) / double(bounds.area());
    result.stoppedEarly = bootstrapCancelled || (ms.mutations < total && ms.b > 0);
    result.pixelSamples.assign(size_t(bounds.area()), 0);
    filmResults(film, lightPaths, result);
    for (const auto& f : depthFilms) result.depthImages.push_back(f->image(lightPaths));
    return result;
}

}  // namespace ps
