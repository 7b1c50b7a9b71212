#include "transport/mlt/pssmlt.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "mc/estimator.h"
#include "mc/primary_sample_sampler.h"
#include "transport/render_monitor.h"
#include "util/error.h"

namespace ps {

Spectrum PSSMLTIntegrator::Li(const Ray&, SampleContext&) const {
    throw std::logic_error("pssmlt is a Markov-chain integrator: render it with renderMetropolis");
}

namespace {

using PathContribution = BDPTIntegrator::PathContribution;

// One thread's tools for evaluating the sample a sampler holds.
struct Evaluator {
    ScratchBuffer scratch;
    PathStats stats;
};

// A sample of the chain: its splats and its target value.
struct ChainState {
    std::vector<PathContribution> splats;
    double f = 0;
};

class Target {
public:
    Target(const Scene& scene, const BDPTIntegrator& bdpt) : scene_(scene), bdpt_(bdpt) {
        const Camera::Params& c = scene.camera().params();
        margin_ = scene.filter().radius();
        filmSize_ = Vec2(float(c.xRes) + 2 * margin_.x, float(c.yRes) + 2 * margin_.y);
        hasLens_ = c.lensRadius > 0;
    }
    // The film position is uniform over the film widened by the filter radius, the area
    // over which the film's splats are normalised (Film::image); then the camera and light
    // subpaths. The target is the luminance of the sum of every strategy's contribution.
    void evaluate(PrimarySampleSampler& sampler, Evaluator& ev, ChainState& out) const {
        sampler.startStream(BDPTIntegrator::kCameraStream);
        Vec2 u = sampler.get2D();
        CameraSample cs;
        cs.pFilm = {-margin_.x + u.x * filmSize_.x, -margin_.y + u.y * filmSize_.y};
        cs.pLens = hasLens_ ? sampler.get2D() : Vec2(0.5f, 0.5f);
        Ray ray = scene_.camera().generateRay(cs);
        bdpt_.contributions(ray, cs.pFilm, sampler, ev.scratch, ev.stats, out.splats);
        ev.scratch.reset();
        double f = 0;
        for (const PathContribution& c : out.splats) f += c.L.luminance();
        out.f = std::isfinite(f) ? f : 0.0;
    }

private:
    const Scene& scene_;
    const BDPTIntegrator& bdpt_;
    Vec2 margin_, filmSize_;
    bool hasLens_ = false;
};

// Keys of the random streams, per bootstrap sample and per chain. The seed is mixed before
// the index enters: keyed on seed ^ constant directly, nearby seeds would give largely the
// same set of keys over a range of indices (shifted), and renders with different seeds would
// share most of their bootstrap samples.
uint64_t bootstrapSeed(uint64_t seed, int64_t i) { return mixWithKey(mix64(seed ^ 0x6a09e667f3bcc908ULL), uint64_t(i)); }
uint64_t chainSeed(uint64_t seed, int chain) { return mixWithKey(mix64(seed ^ 0xbb67ae8584caa73bULL), uint64_t(chain)); }

struct ChainCounts {
    long long proposedLarge = 0, acceptedLarge = 0, proposedSmall = 0, acceptedSmall = 0, invalid = 0, done = 0;
};

}  // namespace

RenderResult renderMetropolis(const Scene& scene, const PSSMLTIntegrator& integrator, const RenderOptions& options) {
    if (!scene.camera().hasImportance())
        throw InputError("integrator \"pssmlt\" splats every path onto the film and needs a perspective camera");
    const MetropolisParams& mp = integrator.params();
    const PixelBounds& bounds = scene.pixelBounds();
    const Camera::Params& cp = scene.camera().params();
    Film film(cp.xRes, cp.yRes, bounds, &scene.filter());
    const Target target(scene, integrator.bdpt());
    PrimarySampleParams pss;
    pss.sigma = mp.sigma;
    pss.largeStepProbability = mp.largeStepProbability;
    pss.streamCount = BDPTIntegrator::kStreamCount;

    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    tbb::enumerable_thread_specific<Evaluator> evaluators;
    tbb::enumerable_thread_specific<ChainState> states;

    RenderResult result;
    MetropolisStats& ms = result.metropolis;
    ms.present = true;

    // Bootstrap: b and the weights of the candidate initial states.
    const int64_t nBoot = std::max(1, mp.bootstrapSamples);
    std::vector<double> weights(size_t(nBoot), 0.0);
    arena.execute([&] {
        tbb::parallel_for(int64_t(0), nBoot, [&](int64_t i) {
            PrimarySampleSampler sampler(bootstrapSeed(options.seed, i), pss);
            sampler.startIteration();
            ChainState& st = states.local();
            target.evaluate(sampler, evaluators.local(), st);
            weights[size_t(i)] = st.f;
        });
    });
    std::vector<double> cumulative(weights.size());
    double sum = 0;
    for (size_t i = 0; i < weights.size(); ++i) cumulative[i] = (sum += weights[i]);
    ms.bootstrapSamples = nBoot;
    ms.b = sum / double(nBoot);

    const long long total = std::max(1LL, (long long)std::max(1, options.spp) * bounds.area());
    const int chains = int(std::min<long long>(std::max(1, mp.chains), total));
    ms.chains = chains;
    std::atomic<bool> stop{false};
    std::atomic<long long> done{0};
    std::vector<ChainCounts> counts(static_cast<size_t>(chains));
    bool replayFailed = false;
    if (!(ms.b > 0)) {
        warning("pssmlt: the " + std::to_string(nBoot) +
                " bootstrap samples found no path that carries light to the camera; the image is black");
    } else {
        Monitor monitor(options.progress, options.timeLimit, options.cancel, stop, done, total);
        std::atomic<bool> replayMismatch{false};
        arena.execute([&] {
            tbb::parallel_for(0, chains, [&](int c) {
                Evaluator& ev = evaluators.local();
                ChainCounts& cc = counts[size_t(c)];
                Rng rng(chainSeed(options.seed, c), 0x3c6ef372fe94f82bULL);
                // The initial state in proportion to its bootstrap value, replayed.
                double pick = rng.uniformDouble() * sum;
                int64_t i = std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin();
                i = std::min<int64_t>(i, nBoot - 1);
                while (i > 0 && weights[size_t(i)] == 0) --i;  // a rounding at the end: the last positive one
                PrimarySampleSampler sampler(bootstrapSeed(options.seed, i), pss);
                sampler.startIteration();
                ChainState x, y;
                target.evaluate(sampler, ev, x);
                sampler.accept();
                if (x.f != weights[size_t(i)]) {
                    replayMismatch = true;
                    return;
                }
                sampler.reseed(chainSeed(options.seed, c));
                const long long n = total / chains + (c < total % chains ? 1 : 0);
                for (long long k = 0; k < n; ++k) {
                    if ((k & 255) == 0 && stop.load(std::memory_order_relaxed)) break;
                    sampler.startIteration();
                    const bool large = sampler.largeStep();
                    target.evaluate(sampler, ev, y);
                    const double a = acceptanceProbability(x.f, y.f);
                    if (!(y.f > 0)) ++cc.invalid;
                    // Expected values: the state with 1 - a, the proposal with a, each
                    // contribution divided by its sample's target value.
                    if (a < 1)
                        for (const PathContribution& pc : x.splats) film.addSplat(pc.pRaster, pc.L * float((1 - a) / x.f), c);
                    if (a > 0)
                        for (const PathContribution& pc : y.splats) film.addSplat(pc.pRaster, pc.L * float(a / y.f), c);
                    ++(large ? cc.proposedLarge : cc.proposedSmall);
                    if (rng.uniformDouble() < a) {
                        sampler.accept();
                        std::swap(x, y);
                        ++(large ? cc.acceptedLarge : cc.acceptedSmall);
                    } else {
                        sampler.reject();
                    }
                    ++cc.done;
                    if ((k & 255) == 255) done.fetch_add(256, std::memory_order_relaxed);
                }
                done.fetch_add(cc.done & 255, std::memory_order_relaxed);
            });
        });
        result.seconds = monitor.elapsed();
        replayFailed = replayMismatch.load();
    }
    if (replayFailed)
        throw std::logic_error("pssmlt: a bootstrap sample replayed with a different contribution");

    for (const ChainCounts& cc : counts) {
        ms.proposedLarge += cc.proposedLarge;
        ms.acceptedLarge += cc.acceptedLarge;
        ms.proposedSmall += cc.proposedSmall;
        ms.acceptedSmall += cc.acceptedSmall;
        ms.invalidProposals += cc.invalid;
        ms.mutations += cc.done;
    }
    for (const Evaluator& ev : evaluators) result.stats += ev.stats;
    // Splats are normalised by "light paths" (Film::image): mutations / b per unit of the
    // target's integral, with the imaging ratio as for BDPT's splats.
    const float imagingRatio = scene.settings().imagingRatio;
    const double lightPaths =
        ms.b > 0 && imagingRatio > 0 && ms.mutations > 0 ? double(ms.mutations) / (ms.b * imagingRatio) : 0.0;
    result.targetSpp = std::max(1, options.spp);
    result.meanSpp = double(ms.mutations) / double(bounds.area());
    result.stoppedEarly = ms.mutations < total && ms.b > 0;
    result.pixelSamples.assign(size_t(bounds.area()), 0);
    filmResults(film, lightPaths, result);
    return result;
}

}  // namespace ps
