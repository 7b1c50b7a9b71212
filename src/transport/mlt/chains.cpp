#include "transport/mlt/metropolis.h"
#include "transport/mlt/bootstrap.h"

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
#include "render/distributed.h"
#include "transport/film_reduction.h"
#include "transport/mlt/chain_checkpoint.h"
#include "transport/mlt/chain_ranks.h"
#include "transport/mlt/startup_budget.h"
#include "transport/render_monitor.h"
#include "transport/spectral_film.h"
#include "util/error.h"

namespace ps {

MetropolisIntegrator::MetropolisIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params,
                                           MisWeighting mis)
    : scene_(scene), bdpt_(scene, maxDepth, mis), params_(params) {
    const Camera::Params& c = scene.camera().params();
    margin_ = scene.filter().radius();
    filmSize_ = Vec2(float(c.xRes) + 2 * margin_.x, float(c.yRes) + 2 * margin_.y);
    if (scene.settings().spectral) sensor_.emplace(scene.settings());
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
    if (!scene_.camera().usesLensSample()) cs.pLens = Vec2(0.5f, 0.5f);
    if (scene_.hasMotion()) {
        // The path's time: a camera-stream value past every block the camera walk reads.
        sampler.seekDimension(bdpt_.subpaths().timeDimension());
        cs.time = sampler.get1D();
    }
    return cs;
}

SampledWavelengths* MetropolisIntegrator::wavelengths(PrimarySampleSampler& sampler, ChainEvaluator& ev) const {
    if (!sensor_) return nullptr;
    sampler.startStream(BDPTIntegrator::kCameraStream);
    sampler.seekDimension(bdpt_.subpaths().timeDimension() + 1);
    ev.lambda = ev.lambdaAfterWalks = SpectralFilm::sampleWavelengths(sampler.get1D());
    return &ev.lambdaAfterWalks;
}

void MetropolisIntegrator::bdptSample(PrimarySampleSampler& sampler, ChainEvaluator& ev,
                                      std::vector<BDPTIntegrator::PathContribution>& out) const {
    CameraSample cs = filmSample(sampler);
    SampledWavelengths* lambda = wavelengths(sampler, ev);
    float weight = 1;
    Ray ray = scene_.camera().generateRay(cs, &weight);
    out.clear();
    if (weight > 0) bdpt_.contributions(ray, cs.pFilm, sampler, ev.scratch, ev.stats, out, -1, lambda);
    ev.scratch.reset();
    for (BDPTIntegrator::PathContribution& c : out) c.L = toRendering(c, ev) * weight;
}

namespace {

using PathContribution = BDPTIntegrator::PathContribution;

// The key of a chain's random streams (its mutations; see bootstrapSeed for why the seed is
// mixed first).
uint64_t chainSeed(uint64_t seed, int chain) { return mixWithKey(mix64(seed ^ 0xbb67ae8584caa73bULL), uint64_t(chain)); }

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

// Every chain's counts on rank 0, each from the process that ran it (chain_ranks.h).
void gatherCounts(std::vector<ChainCounts>& counts, size_t depths) {
    if (distributed::size() == 1) return;
    const size_t stride = 6 + 3 * depths;
    chain_ranks::ChainRecords records(int(counts.size()), stride);
    for (int c = 0; c < int(counts.size()); ++c) {
        if (!chain_ranks::ownsChain(c)) continue;
        const ChainCounts& cc = counts[size_t(c)];
        size_t k = 0;
        for (long long v : {cc.proposedLarge, cc.acceptedLarge, cc.proposedSmall, cc.acceptedSmall, cc.invalid, cc.done})
            records.put(c, k++, v);
        for (size_t d = 0; d < depths; ++d) {
            records.put(c, k++, cc.proposedAt[d]);
            records.put(c, k++, cc.acceptedAt[d]);
            records.put(c, k++, cc.shareAt[d]);
        }
    }
    distributed::Purpose purpose("chain counts");
    records.gatherToRoot();
    if (!distributed::isRoot()) return;
    for (int c = 0; c < int(counts.size()); ++c) {
        ChainCounts& cc = counts[size_t(c)];
        size_t k = 0;
        for (long long* v : {&cc.proposedLarge, &cc.acceptedLarge, &cc.proposedSmall, &cc.acceptedSmall, &cc.invalid, &cc.done})
            *v = records.count(c, k++);
        cc.proposedAt.assign(depths, 0);
        cc.acceptedAt.assign(depths, 0);
        cc.shareAt.assign(depths, 0.0);
        for (size_t d = 0; d < depths; ++d) {
            cc.proposedAt[d] = records.count(c, k++);
            cc.acceptedAt[d] = records.count(c, k++);
            cc.shareAt[d] = records.real(c, k++);
        }
    }
}

// A chain's whole state between passes (chain_checkpoint.h), and back.
void saveChain(const Chain& ch, const ChainCounts& cc, ByteWriter& out) {
    out.put(ch.rng);
    out.put(int64_t(ch.remaining));
    out.put(ch.x.f);
    out.put(int32_t(ch.x.depth));
    out.put(int32_t(ch.x.strategy));
    out.putVector(ch.x.splats);
    ch.sampler->save(out);
    for (long long v : {cc.proposedLarge, cc.acceptedLarge, cc.proposedSmall, cc.acceptedSmall, cc.invalid, cc.done})
        out.put(int64_t(v));
    out.putVector(cc.proposedAt);
    out.putVector(cc.acceptedAt);
    out.putVector(cc.shareAt);
}

void loadChain(ByteReader in, const PrimarySampleParams& pss, size_t depths, Chain& ch, ChainCounts& cc) {
    ch.rng = in.get<Rng>();
    ch.remaining = in.get<int64_t>();
    ch.x.f = in.get<double>();
    ch.x.depth = in.get<int32_t>();
    ch.x.strategy = in.get<int32_t>();
    ch.x.splats = in.getVector<PathContribution>();
    ch.sampler = std::make_unique<PrimarySampleSampler>(0, pss);
    ch.sampler->load(in);
    for (long long* v : {&cc.proposedLarge, &cc.acceptedLarge, &cc.proposedSmall, &cc.acceptedSmall, &cc.invalid, &cc.done})
        *v = in.get<int64_t>();
    cc.proposedAt = in.getVector<long long>();
    cc.acceptedAt = in.getVector<long long>();
    cc.shareAt = in.getVector<double>();
    if (cc.proposedAt.size() != depths || cc.acceptedAt.size() != depths || cc.shareAt.size() != depths ||
        ch.remaining < 0 || !in.atEnd())
        in.fail();
}

// What the chains and the statistics need of the bootstrap, for a checkpoint, and back.
std::vector<char> saveBootstrap(const Bootstrap& boot, int64_t samples, const PilotImportance& importance) {
    ByteWriter out;
    out.put(boot.b);
    out.put(boot.bRelativeError);
    out.put(samples);
    out.put(boot.pilotSamples);
    out.putVector(boot.choice.weights());
    out.putVector(boot.groups.count);
    importance.save(out);
    return std::move(out.bytes());
}

Bootstrap loadBootstrap(ByteReader in, const MetropolisIntegrator& integrator, int64_t& samples,
                        PilotImportance& importance) {
    Bootstrap boot;
    boot.b = in.get<double>();
    boot.bRelativeError = in.get<double>();
    samples = in.get<int64_t>();
    boot.pilotSamples = in.get<int64_t>();
    const std::vector<float> weights = in.getVector<float>();
    boot.groups.count = in.getVector<int64_t>();
    importance.load(in);
    boot.choice = integrator.defaultChoice();
    if (int(weights.size()) != boot.choice.size() || !in.atEnd()) in.fail();
    if (!weights.empty()) boot.choice = boot.choice.withWeights(weights);
    return boot;
}

}  // namespace

void MetropolisIntegrator::bootstrapSample(PrimarySampleSampler& sampler, int, double scale,
                                           const StrategyChoice& choice, ChainEvaluator& ev,
                                           std::vector<BootstrapState>& out) const {
    out.clear();
    evaluate(sampler, choice, ev, ev.sample);
    if (ev.sample.f > 0) out.push_back({ev.sample.strategy, scale * ev.sample.f, ev.sample.f});
}

RenderResult renderMetropolis(const Scene& scene, const MetropolisIntegrator& integrator, const RenderOptions& options) {
    const std::string name = integrator.name();
    const MetropolisParams& mp = integrator.params();
    const PixelBounds& bounds = scene.pixelBounds();
    const Camera::Params& cp = scene.camera().params();
    Film film(cp.xRes, cp.yRes, bounds, &scene.filter(), options.filmMoments());
    setChainClamp(film, scene.settings());
    const int depths = integrator.maxDepth() + 1;
    std::vector<std::unique_ptr<Film>> depthFilms;
    if (mp.depthImages)
        for (int d = 0; d < depths; ++d) {
            depthFilms.push_back(std::make_unique<Film>(cp.xRes, cp.yRes, bounds, &scene.filter()));
            setChainClamp(*depthFilms.back(), scene.settings());
        }
    PrimarySampleParams pss;
    pss.sigma = mp.sigma;
    pss.largeStepProbability = mp.largeStepProbability;
    pss.streamCount = integrator.streamCount();
    // Camera steps (thesis 11.4.3's lens perturbation, in primary sample space): a share of
    // the small steps moves the camera subpath and the connection and keeps the light
    // subpath and the strategy, which are what is hard to find where light comes through a
    // narrow opening. A light-tracing state (t = 1) moves its light subpath instead
    // (MetropolisIntegrator::partialStepKind), in the order of PartialStepKind.
    pss.partialStepProbability = mp.cameraStepProbability;
    constexpr uint32_t kConnection = 1u << BDPTIntegrator::kConnectionStream;
    pss.partialSteps = {{1u << BDPTIntegrator::kCameraStream | kConnection, mp.sigma},
                        {1u << BDPTIntegrator::kLightStream | kConnection, mp.sigma}};

    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    // Two-stage MLT: the pilot image every evaluator divides the target by (at() is 1 until
    // the pilot has made it).
    int64_t nPilot = mp.twoStageSamples();
    PilotImportance importance(bounds, nPilot, mp.twoStageBlackLevel, scene.settings().imagingRatio);
    tbb::enumerable_thread_specific<ChainEvaluator> evaluators([&importance] {
        ChainEvaluator ev;
        ev.importance = &importance;
        return ev;
    });
    tbb::enumerable_thread_specific<ChainState> proposals;

    RenderResult result;
    MetropolisStats& ms = result.metropolis;
    ms.present = true;
    // Mutations per pixel already made, as a uniform render's resumed samples per pixel.
    if (options.resume) result.resumedSpp = int(options.resume->samples / std::max<long long>(1, bounds.area()));
    ms.multiplexed = integrator.choosesDepth();

    // Bootstrap: b, the strategy choice and the weights of the candidate initial states. It
    // counts against the time budget, and a cancellation during it leaves a black image (b
    // unknown). Over several processes it is shared (chain_ranks.h), their clocks start together.
    // A resumed render takes the bootstrap's results and every chain's state from its
    // checkpoint (chain_checkpoint.h) and runs no bootstrap.
    const long long total = std::max(1LL, (long long)std::max(1, options.spp) * bounds.area());
    const int chains = int(std::min<long long>(std::max(1, mp.chains), total));
    ChainCheckpoints checkpoints(options, chains, total);
    distributed::barrier();
    const auto startTime = std::chrono::steady_clock::now();
    std::atomic<long long> startupDone{0};
    BootstrapContext bctx{integrator, pss, options.seed, options.cancel, arena, evaluators, &startupDone};
    int64_t nBoot = 0, nAll = bootstrapIndexCount(integrator);
    if (!checkpoints.resuming()) {
        // Within a time budget, a start-up that fits a quarter of it (startup_budget.h): the
        // one --bootstrap N' gives, N' as the statistics' bootstrap and pilot samples say.
        const int64_t probed = startupProbeSamples(nAll + nPilot);
        const double fraction = startupFraction(options.timeLimit, nAll + nPilot, probed,
                                                [&] { probeBootstrap(bctx, probed); });
        if (fraction < 1) {
            const int groups = std::max(1, integrator.bootstrapGroups());
            nAll = std::max<int64_t>(groups, scaledCount(nAll, fraction, std::max<int64_t>(256, 4 * groups)));
            if (nPilot > 0) {
                nPilot = mp.twoStageSamples(nAll);
                importance = PilotImportance(bounds, nPilot, mp.twoStageBlackLevel, scene.settings().imagingRatio);
            }
        }
    }
    Bootstrap boot;
    {
        std::atomic<bool> shown{false};
        Monitor monitor(options.progress && distributed::isRoot() && !checkpoints.resuming(), 0, nullptr, shown,
                        startupDone, std::max<long long>(1, (nAll + nPilot + distributed::size() - 1) / distributed::size()),
                        "bootstrap", &options.onProgress);
        if (!checkpoints.resuming()) {
            runImportancePilot(bctx, nAll, nPilot, importance);
            boot = runBootstrap(bctx, nAll);
            nBoot = int64_t(boot.weights.size());
        } else {
            boot = loadBootstrap(checkpoints.bootstrap(), integrator, nBoot, importance);
        }
    }
    ms.twoStageSamples = nPilot;
    const std::vector<char> bootBytes = options.checkpoint ? saveBootstrap(boot, nBoot, importance) : std::vector<char>();
    const StrategyChoice& choice = boot.choice;
    const bool bootstrapCancelled = boot.cancelled;
    ms.bootstrapSamples = nBoot;
    ms.pilotSamples = boot.pilotSamples;
    ms.b = boot.b;
    ms.bRelativeError = boot.bRelativeError;
    ms.depths.assign(size_t(depths), {});
    for (int k = 0; k < choice.size(); ++k)
        if (const int d = choice.groupOf(k); d < depths) ms.depths[size_t(d)].chosen += choice.pmf(k);
    if (integrator.bootstrapGroups() == depths)
        for (int d = 0; d < depths; ++d) ms.depths[size_t(d)].bootstrapSamples = boot.groups.count[size_t(d)];

    ms.chains = chains;
    std::atomic<bool> stop{false};
    std::atomic<long long> done{0};
    std::vector<ChainCounts> counts(static_cast<size_t>(chains));
    bool replayFailed = false;
    long long doneBefore = 0;  // this process's chains' mutations resumed from a checkpoint
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
        // This process's chains (chain_ranks.h) and their mutations (its progress bar's total).
        long long mineTotal = 0;
        const std::vector<int> mine = chain_ranks::ownedChains(chains, total, &mineTotal);
        const auto chainsStart = std::chrono::steady_clock::now();
        std::atomic<bool> replayMismatch{false};
        // Every chain starts from a bootstrap state, then all advance in passes of a few
        // hundred mutations each, so that a render stopped early (time budget, Ctrl-C) has
        // mutations from every chain, not the whole of a few.
        std::vector<Chain> all(static_cast<size_t>(chains));
        arena.execute([&] {
            tbb::parallel_for(size_t(0), mine.size(), [&](size_t m) {
                const int c = mine[m];
                Chain& ch = all[size_t(c)];
                ChainCounts& cc = counts[size_t(c)];
                cc.proposedAt.assign(size_t(depths), 0);
                cc.acceptedAt.assign(size_t(depths), 0);
                cc.shareAt.assign(size_t(depths), 0.0);
                if (checkpoints.resuming()) {
                    loadChain(checkpoints.chain(c), pss, size_t(depths), ch, cc);
                    ch.remaining += checkpoints.addedMutations(c);
                    return;
                }
                ch.rng = Rng(chainSeed(options.seed, c), 0x3c6ef372fe94f82bULL);
                if (!startChain(bctx, boot, ch.rng, ch.sampler, ch.x)) {
                    replayMismatch = true;
                    return;
                }
                ch.sampler->reseed(chainSeed(options.seed, c));
                ch.remaining = chain_ranks::chainMutations(total, chains, c);
            });
        });
        constexpr long long kPass = 256;
        // The chain with the most mutations left sets the passes (a resumed render's chains
        // may stand a pass apart: a render stopped within a pass).
        long long mostLeft = 0;
        for (int c : mine) {
            mostLeft = std::max(mostLeft, all[size_t(c)].remaining);
            doneBefore += counts[size_t(c)].done;
        }
        // The progress bar counts this run's mutations (a resumed render's bar ends at 100%);
        // the chains' start counts against the budget.
        const double startSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - chainsStart).count();
        if (chainTime > 0) chainTime = std::max(chainTime - startSeconds, 1e-6);
        Monitor monitor(options.progress && distributed::isRoot(), chainTime, options.cancel, stop, done,
                        std::max(1LL, mineTotal - doneBefore), "rendering", &options.onProgress);
        // The processes agree after every pass whether to go on (a time limit, a signal to any).
        bool halt = false;
        {
            distributed::Purpose purpose("stop decisions");
            mostLeft = distributed::maxOf(mostLeft);
            replayFailed = distributed::anyOf(replayMismatch.load());
            halt = replayFailed || distributed::anyOf(stop.load());
        }
        for (long long pass = 0; pass * kPass < mostLeft && !halt; ++pass) {
            arena.execute([&] {
                tbb::parallel_for(size_t(0), mine.size(), [&](size_t m) {
                    if (stop.load(std::memory_order_relaxed)) return;
                    const int c = mine[m];
                    Chain& ch = all[size_t(c)];
                    const long long n = std::min(ch.remaining, kPass);
                    ChainEvaluator& ev = evaluators.local();
                    ChainState& y = proposals.local();
                    ChainCounts& cc = counts[size_t(c)];
                    PrimarySampleSampler& sampler = *ch.sampler;
                    for (long long k = 0; k < n; ++k) {
                        sampler.startIterationOfKind(integrator.partialStepKind(ch.x));
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
            {
                distributed::Purpose purpose("stop decisions");
                halt = distributed::anyOf(stop.load());
            }
            // A checkpoint when one is due, and a last one when the render stops or ends.
            if (checkpoints.due(halt || (pass + 1) * kPass >= mostLeft)) {
                PathStats stats;
                for (const ChainEvaluator& ev : evaluators) stats += ev.stats;
                long long doneHere = -doneBefore;
                for (int c : mine) doneHere += counts[size_t(c)].done;
                checkpoints.write(
                    film, bootBytes, mine,
                    [&](int c, ByteWriter& out) { saveChain(all[size_t(c)], counts[size_t(c)], out); }, doneHere,
                    stats, result);
            }
        }
        result.seconds += startSeconds + monitor.elapsed();
    }
    if (replayFailed)
        throw std::logic_error(name + ": a bootstrap sample replayed with a different contribution");

    // Every process's films, counts and statistics on rank 0; the others are done.
    long long mutationsHere = -doneBefore;  // this run's
    for (int c = 0; c < chains; ++c) mutationsHere += counts[size_t(c)].done;
    for (const ChainEvaluator& ev : evaluators) result.stats += ev.stats;
    gatherCounts(counts, size_t(depths));
    const bool root = reduceToRoot(film, mutationsHere, result, checkpoints.resume());
    if (distributed::size() > 1)
        for (const auto& f : depthFilms) sumFilmInto(*f, *f);
    if (!root) return result;

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
    // Each iteration's shares sum to 1 with the plain target, to B with the two-stage one.
    double shares = 0;
    for (const MetropolisStats::Depth& d : ms.depths) shares += d.share;
    for (MetropolisStats::Depth& d : ms.depths) d.share = shares > 0 ? d.share / shares : 0.0;
    std::vector<long long> chainDone, chainAccepted, chainProposed;
    for (const ChainCounts& cc : counts) {
        chainDone.push_back(cc.done);
        chainAccepted.push_back(cc.acceptedLarge + cc.acceptedSmall);
        chainProposed.push_back(cc.proposedLarge + cc.proposedSmall);
    }
    chain_ranks::perProcess(ms, chainDone, chainAccepted, chainProposed);
    const double lightPaths = finishChains(scene, film, options, total, bootstrapCancelled, result);
    for (const auto& f : depthFilms) result.depthImages.push_back(f->image(lightPaths));
    return result;
}

double finishChains(const Scene& scene, const Film& film, const RenderOptions& options, long long total,
                    bool bootstrapCancelled, RenderResult& result) {
    const MetropolisStats& ms = result.metropolis;
    const PixelBounds& bounds = scene.pixelBounds();
    // Splats are normalised by "light paths" (Film::image): mutations / b per unit of the
    // target's integral, with the imaging ratio as for BDPT's splats.
    const float imagingRatio = scene.settings().imagingRatio;
    const double lightPaths =
        ms.b > 0 && imagingRatio > 0 && ms.mutations > 0 ? double(ms.mutations) / (ms.b * imagingRatio) : 0.0;
    result.targetSpp = std::max(1, options.spp);
    result.meanSpp = double(ms.mutations) / double(bounds.area());
    result.stoppedEarly = bootstrapCancelled || (ms.mutations < total && ms.b > 0);
    if (options.pixelSamples) result.pixelSamples.assign(size_t(bounds.area()), 0);
    filmResults(film, lightPaths, scene.settings(), options, result);
    return lightPaths;
}

}  // namespace ps
