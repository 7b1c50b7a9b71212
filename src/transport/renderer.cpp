#include "transport/renderer.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <numeric>

#include <tbb/task_arena.h>

#include "mc/estimator.h"
#include "transport/checkpoint.h"
#include "transport/film_reduction.h"
#include "transport/spectral_film.h"
#include "mc/sampler.h"
#include "render/distributed.h"

#include "util/error.h"
#include "util/memory_limit.h"

#include "transport/mlt/metropolis.h"
#include "transport/mlt/veach/veach_mlt.h"
#include "transport/render_monitor.h"
#include "transport/sample_passes.h"

namespace ps {

namespace {

// Where a uniform render stands: passes [0, s0) whole, the next (or current) pass of `pass`
// samples per pixel, of which the samples in `partial` (per pixel, bit k: index s0 + k; empty:
// none) are already in the film.
struct UniformProgress {
    int s0 = 0, pass = 1;
    std::vector<uint64_t> partial;
};

// Passes of growing size: an early stop leaves every pixel with a similar count, and each
// pixel is normalised by its own weights, so the image stays unbiased. Processes of one
// render agree after every pass whether to go on. afterPass(s1, next pass) runs after every
// whole pass but the last. With `track`, a pass that stops leaves in at.partial the samples
// this process took of it (with those taken before), for a last checkpoint.
bool renderUniform(SamplePasses& passes, Film& film, int spp, UniformProgress& at, bool track,
                   const std::function<void(int, int)>& afterPass) {
    std::vector<uint64_t> taken;
    while (at.s0 < spp) {
        const int s1 = std::min(spp, at.s0 + at.pass);
        if (track) taken.assign(passes.pixelCount(), 0);
        const bool whole = passes.run(
            film, [&](size_t p) { return SampleSpan{at.s0, s1, at.partial.empty() ? 0 : at.partial[p]}; },
            SamplePasses::Stream::Main, track ? &taken : nullptr);
        if (distributed::Purpose p("stop decisions"); distributed::anyOf(!whole)) {
            if (track) {
                if (at.partial.empty()) at.partial.assign(taken.size(), 0);
                for (size_t i = 0; i < taken.size(); ++i) at.partial[i] |= taken[i];
            }
            return false;
        }
        at.partial.clear();
        at.s0 = s1;
        at.pass = std::min(at.pass * 2, 64);
        if (at.s0 < spp) afterPass(at.s0, at.pass);
    }
    return true;
}

// The light paths behind the film's splats: one per camera sample, the imaging ratio scaling
// splats as well (0 with no imaging).
double splatLightPaths(const Film& film, const Scene& scene) {
    const float imagingRatio = scene.settings().imagingRatio;
    return imagingRatio > 0 ? film.meanSamplesPerPixel() * double(film.bounds().area()) / imagingRatio : 0.0;
}

// The shadow-ray roulette's threshold from the film so far: `share` of its mean pixel value
// (channel mean), in the units of a sample's radiance (before the imaging ratio).
float shadowTau(const Film& film, const Scene& scene, float share) {
    const float imagingRatio = scene.settings().imagingRatio;
    const Image image = film.image(splatLightPaths(film, scene));
    double sum = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) sum += image.get(x, y).average();
    const double mean = sum / std::max(1.0, double(image.width) * image.height);
    return imagingRatio > 0 && std::isfinite(mean) ? float(share * mean / imagingRatio) : 0.0f;
}

// Before the film is made: its bytes against the memory limit, named by the Film directive.
void requireFilmMemory(const Scene& scene, const Integrator& integrator, const RenderOptions& options) {
    const PixelBounds& b = scene.pixelBounds();
    const Camera::Params& c = scene.camera().params();
    // Threads that may splat: an arena never runs more than the machine's concurrency.
    int threads = tbb::this_task_arena::max_concurrency();
    if (options.threads > 0) threads = std::min(threads, options.threads);
    const double pixels = double(b.area());
    double bytes = Film::estimateBytes(pixels, integrator.splats(), threads, options.filmMoments());
    // A two-stage render also holds a pilot film and its allocation arrays, about one more
    // film's worth. (The sequential rule's arrays are gone before the output images exist.)
    // So does a sequential one over several processes (rank 0's sum of the films).
    if (options.adaptive == AdaptiveMode::TwoStage ||
        (options.adaptive == AdaptiveMode::Sequential && distributed::size() > 1))
        bytes += Film::estimateBytes(pixels, false, 1);
    std::string what = "Film " + std::to_string(c.xRes) + "x" + std::to_string(c.yRes);
    if (b.area() != (long long)c.xRes * c.yRes)
        what += " (crop " + std::to_string(b.width()) + "x" + std::to_string(b.height()) + ")";
    if (integrator.splats()) what += " with splat buffers for " + std::to_string(threads) + " thread(s)";
    requireMemory(scene.settings().filmLoc, what, bytes);
}

}  // namespace

void filmResults(const Film& film, double lightPaths, const RenderSettings& settings, const RenderOptions& options,
                 RenderResult& result) {
    result.lightPaths = lightPaths;
    result.image = film.image(lightPaths);
    if (const auto& m = settings.outputColorMatrix)
        for (int y = 0; y < result.image.height; ++y)
            for (int x = 0; x < result.image.width; ++x) {
                const Spectrum v = result.image.get(x, y);
                result.image.set(x, y, {(*m)[0] * v.r + (*m)[1] * v.g + (*m)[2] * v.b,
                                        (*m)[3] * v.r + (*m)[4] * v.g + (*m)[5] * v.b,
                                        (*m)[6] * v.r + (*m)[7] * v.g + (*m)[8] * v.b});
            }
    if (options.varianceImage) result.variance = film.varianceImage(lightPaths);
    result.rejectedSamples = film.rejectedSamples();
    if (options.errorEstimate) result.error = film.errorEstimate(lightPaths);
    result.efficiency = efficiency(result.error.meanRelativeVariance, result.seconds);
}

void checkRenderable(const Scene& scene, const Integrator& integrator, const RenderOptions& options) {
    if (options.adaptive != AdaptiveMode::None && integrator.splats())
        throw InputError("adaptive sampling needs an integrator whose pixels come from their own samples "
                         "(path); light tracing, BDPT and Metropolis splat onto the whole film");
    if ((options.resume || options.checkpoint) && options.adaptive != AdaptiveMode::None)
        throw InputError("adaptive sampling (--adaptive) does not yet write or resume checkpoints: path, light and "
                         "bdpt with uniform sampling and the Metropolis integrators do");
    if (scene.settings().spectral) requireSpectralSupport(integrator, scene.settings().integrator);
    requireFilmMemory(scene, integrator, options);
    if (auto* veach = dynamic_cast<const VeachMLTIntegrator*>(&integrator)) requireVeachMLTSupport(scene, *veach);
}

RenderResult render(const Scene& scene, const Integrator& integrator, const RenderOptions& options) {
    checkRenderable(scene, integrator, options);
    auto* veach = dynamic_cast<const VeachMLTIntegrator*>(&integrator);
    auto* mlt = dynamic_cast<const MetropolisIntegrator*>(&integrator);
    // Markov chains have their own driver: a chain is not a per-camera-ray estimate.
    if (mlt) return renderMetropolis(scene, *mlt, options);
    if (veach) return renderVeachMLT(scene, *veach, options);
    const PixelBounds& bounds = scene.pixelBounds();
    Film film(scene.camera().params().xRes, scene.camera().params().yRes, bounds,
              integrator.splats() ? &scene.filter() : nullptr, options.filmMoments());
    film.setMaxComponentValue(scene.settings().maxComponentValue, scene.settings().imagingRatio,
                             sensorFromRendering(scene.settings()));
    const int spp = std::max(1, options.spp);

    std::atomic<bool> stop{false};
    std::atomic<long long> samplesDone{0};
    SamplePasses passes(scene, integrator, options, stop, samplesDone);
    RenderResult result;
    result.targetSpp = spp;
    bool complete = false;
    // Where a resumed render stands (its sums join the film on rank 0 at the end).
    const CheckpointState* resume = options.resume;
    UniformProgress at;
    if (resume) {
        at = {std::min(resume->samplesPerPixel, spp), resume->passSize, resume->partial};
        if (!at.partial.empty() && at.partial.size() != film.pixelCount())
            throw InputError("--resume: the checkpoint's partial pass has another size than this render's film");
    }
    const int s0 = at.s0;
    result.resumedSpp = s0;
    // After a whole pass, once checkpointEvery seconds have passed (the processes agree): the
    // films' sums, with the resumed ones, to rank 0, which writes them.
    auto lastCheckpoint = std::chrono::steady_clock::now();
    auto afterPass = [&](int s1, int nextPass) {
        if (options.shadowRoulette > 0) passes.setShadowTau(shadowTau(film, scene, options.shadowRoulette));
        if (options.checkpointEvery < 0 || !options.checkpoint) return;
        distributed::Purpose purpose("checkpoint");
        const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - lastCheckpoint).count();
        if (!distributed::anyOf(since >= options.checkpointEvery)) return;
        CheckpointState state;
        state.samplesPerPixel = s1;
        state.passSize = nextPass;
        state.samples = passes.samplesDone();
        state.stats = passes.stats();
        if (sumAllToRoot(film, state, resume)) options.checkpoint(state);
        ++result.checkpoints;
        lastCheckpoint = std::chrono::steady_clock::now();
    };
    // One progress bar, rank 0's, over its share; the clocks of all processes start together.
    const int ranks = distributed::size();
    std::unique_ptr<Film> pilot;  // a two-stage render's first stage
    distributed::barrier();
    {
        Monitor monitor(options.progress && distributed::isRoot(), options.timeLimit, options.cancel, stop, samplesDone,
                        (bounds.area() * (spp - s0) + ranks - 1) / ranks, "rendering", &options.onProgress);
        switch (options.adaptive) {
            case AdaptiveMode::None:
                complete = renderUniform(passes, film, spp, at, bool(options.checkpoint), afterPass);
                break;
            case AdaptiveMode::Sequential: {
                distributed::Purpose purpose("adaptive");
                complete = renderSequential(passes, film, monitor, spp);
                break;
            }
            case AdaptiveMode::TwoStage: {
                distributed::Purpose purpose("adaptive");
                pilot = std::make_unique<Film>(film.xRes(), film.yRes(), film.bounds());
                pilot->setMaxComponentValue(film.maxComponentValue(), 1, film.clampSpace());  // its pixels may stand in for the film's
                complete = renderTwoStage(passes, film, *pilot, monitor, spp);
                break;
            }
        }
        result.seconds = monitor.elapsed();
    }
    result.stats = passes.stats();
    // A last checkpoint, of everything taken: stopped early (a signal, --time), the stopped
    // pass's samples included, so that no finished work is lost; at the end, so that a resume
    // can raise --spp.
    const bool finalCheckpoint = options.checkpoint && options.adaptive == AdaptiveMode::None;
    if (finalCheckpoint) {
        distributed::Purpose purpose("checkpoint");
        distributed::orToRoot(at.partial);
    }
    if (!reduceToRoot(film, passes.samplesDone(), result, resume)) return result;
    // Pixels a stop left without second-stage samples: the (whole) pilot's stand in.
    if (pilot) film.adoptEmptyPixels(*pilot);
    if (finalCheckpoint) {
        CheckpointState state;
        state.samplesPerPixel = at.s0;
        state.passSize = at.pass;
        state.partial = std::move(at.partial);
        state.sums = film.accumulators();
        state.samples = std::accumulate(result.distributed.rankSamples.begin(), result.distributed.rankSamples.end(), 0LL) +
                        (resume ? resume->samples : 0);
        state.stats = result.stats;
        int partial = 0;
        for (uint64_t bits : state.partial) partial += bits != 0;
        result.checkpointKept = std::to_string(state.samplesPerPixel) + " of " + std::to_string(spp) + " spp in every pixel";
        if (partial > 0)
            result.checkpointKept += ", and samples of the next pass in " + std::to_string(partial) + " of " +
                                     std::to_string(state.partial.size()) + " pixels";
        options.checkpoint(state);
        ++result.checkpoints;
    }
    const double lightPaths = splatLightPaths(film, scene);
    result.meanSpp = (double(std::accumulate(result.distributed.rankSamples.begin(), result.distributed.rankSamples.end(), 0LL)) +
                      double(resume ? resume->samples : 0)) /
                     double(bounds.area());
    if (options.pixelSamples) result.pixelSamples = film.sampleCounts();
    result.stoppedEarly = !complete;
    filmResults(film, lightPaths, scene.settings(), options, result);
    // Independently scrambled sets: a splatting film's half-images are two groups of them
    // (SamplePasses); other films' pixels take the spread of their sets' means.
    if (passes.scramblingsEstimate()) result.scramblings = options.scramblings;
    if (const ScrambledPixelVariance* sv = passes.scrambledVariance(); sv && options.errorEstimate) {
        result.error = sv->errorEstimate();
        result.efficiency = efficiency(result.error.meanRelativeVariance, result.seconds);
    }
    if (options.techniqueFigures) {
        result.techniques = integrator.techniques();
        result.techniqueFigures = passes.techniqueTally().figures(result.seconds);
        result.techniqueBatches = passes.techniqueBatches();
    }
    return result;
}

}  // namespace ps
