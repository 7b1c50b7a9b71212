#include "transport/renderer.h"

#include <algorithm>
#include <numeric>

#include <tbb/task_arena.h>

#include "mc/estimator.h"
#include "mc/sampler.h"
#include "render/distributed.h"

#include "util/error.h"
#include "util/memory_limit.h"

#include "transport/mlt/metropolis.h"
#include "transport/render_monitor.h"
#include "transport/sample_passes.h"

namespace ps {

namespace {

// Passes of growing size: an early stop leaves every pixel with a similar count, and each
// pixel is normalised by its own weights, so the image stays unbiased. Processes of one
// render agree after every pass whether to go on.
bool renderUniform(SamplePasses& passes, Film& film, int spp) {
    int s0 = 0, pass = 1;
    while (s0 < spp) {
        int s1 = std::min(spp, s0 + pass);
        if (distributed::anyOf(!passes.run(film, [&](size_t) { return SampleSpan{s0, s1}; }))) return false;
        s0 = s1;
        pass = std::min(pass * 2, 64);
    }
    return true;
}

// Before the film is made: its bytes against the memory limit, named by the Film directive.
void requireFilmMemory(const Scene& scene, const Integrator& integrator, const RenderOptions& options) {
    const PixelBounds& b = scene.pixelBounds();
    const Camera::Params& c = scene.camera().params();
    // Threads that may splat: an arena never runs more than the machine's concurrency.
    int threads = tbb::this_task_arena::max_concurrency();
    if (options.threads > 0) threads = std::min(threads, options.threads);
    const double pixels = double(b.area());
    double bytes = Film::estimateBytes(pixels, integrator.splats(), threads);
    // A two-stage render also holds a pilot film and its allocation arrays, about one more
    // film's worth. (The sequential rule's arrays are gone before the output images exist.)
    if (options.adaptive == AdaptiveMode::TwoStage) bytes += Film::estimateBytes(pixels, false, 1);
    std::string what = "Film " + std::to_string(c.xRes) + "x" + std::to_string(c.yRes);
    if (b.area() != (long long)c.xRes * c.yRes)
        what += " (crop " + std::to_string(b.width()) + "x" + std::to_string(b.height()) + ")";
    if (integrator.splats()) what += " with splat buffers for " + std::to_string(threads) + " thread(s)";
    requireMemory(scene.settings().filmLoc, what, bytes);
}

// Sums every process's film and statistics into rank 0's (exact integer sums: the same bits
// as one process taking every sample). False on the other ranks, whose film is then partial.
bool reduceToRoot(Film& film, const SamplePasses& passes, RenderResult& result) {
    DistributedStats& d = result.distributed;
    d.ranks = distributed::size();
    for (double n : distributed::gatherToRoot(double(passes.samplesDone()))) d.rankSamples.push_back((long long)n);
    d.rankSeconds = distributed::gatherToRoot(result.seconds);
    if (d.ranks == 1) return true;
    const distributed::Traffic before = distributed::traffic();
    Film::Accumulators sums = film.accumulators();
    distributed::sumToRoot(sums.fixed);
    distributed::sumToRoot(sums.counts);
    const PathStats& s = result.stats;
    std::vector<int64_t> stats{int64_t(s.cameraPaths), int64_t(s.lightPaths), int64_t(s.rays), int64_t(s.shadowRays),
                               int64_t(s.guarded)};
    distributed::sumToRoot(stats);
    d.reductionBytes = distributed::traffic().bytes - before.bytes;
    d.reductionSeconds = distributed::traffic().seconds - before.seconds;
    if (!distributed::isRoot()) return false;
    film.setAccumulators(sums);
    result.stats = {uint64_t(stats[0]), uint64_t(stats[1]), uint64_t(stats[2]), uint64_t(stats[3]), uint64_t(stats[4])};
    return true;
}

}  // namespace

void filmResults(const Film& film, double lightPaths, RenderResult& result) {
    result.lightPaths = lightPaths;
    result.image = film.image(lightPaths);
    result.variance = film.varianceImage(lightPaths);
    result.rejectedSamples = film.rejectedSamples();
    result.error = film.errorEstimate(lightPaths);
    result.efficiency = efficiency(result.error.meanRelativeVariance, result.seconds);
}

RenderResult render(const Scene& scene, const Integrator& integrator, const RenderOptions& options) {
    if (options.adaptive != AdaptiveMode::None && integrator.splats())
        throw InputError("adaptive sampling needs an integrator whose pixels come from their own samples "
                         "(path); light tracing, BDPT and Metropolis splat onto the whole film");
    auto* mlt = dynamic_cast<const MetropolisIntegrator*>(&integrator);
    if (distributed::size() > 1 && (mlt || options.adaptive != AdaptiveMode::None))
        throw InputError(std::string(mlt ? "Metropolis (pssmlt, mmlt)" : "adaptive sampling (--adaptive)") +
                         " does not yet run over several processes: render it with one (without mpirun, or -n 1); "
                         "path, light and bdpt with uniform sampling do");
    requireFilmMemory(scene, integrator, options);
    // Markov chains have their own driver: a chain is not a per-camera-ray estimate.
    if (mlt) return renderMetropolis(scene, *mlt, options);
    const PixelBounds& bounds = scene.pixelBounds();
    Film film(scene.camera().params().xRes, scene.camera().params().yRes, bounds,
              integrator.splats() ? &scene.filter() : nullptr);
    film.setMaxComponentValue(scene.settings().maxComponentValue, scene.settings().imagingRatio);
    const int spp = std::max(1, options.spp);

    std::atomic<bool> stop{false};
    std::atomic<long long> samplesDone{0};
    SamplePasses passes(scene, integrator, options, stop, samplesDone);
    RenderResult result;
    result.targetSpp = spp;
    bool complete = false;
    // One progress bar, rank 0's, over its share; the clocks of all processes start together.
    const int ranks = distributed::size();
    distributed::barrier();
    {
        Monitor monitor(options.progress && distributed::isRoot(), options.timeLimit, options.cancel, stop, samplesDone,
                        (bounds.area() * spp + ranks - 1) / ranks);
        switch (options.adaptive) {
            case AdaptiveMode::None: complete = renderUniform(passes, film, spp); break;
            case AdaptiveMode::Sequential: complete = renderSequential(passes, film, monitor, spp); break;
            case AdaptiveMode::TwoStage: complete = renderTwoStage(passes, film, monitor, spp); break;
        }
        result.seconds = monitor.elapsed();
    }
    result.stats = passes.stats();
    if (!reduceToRoot(film, passes, result)) return result;
    // Every camera sample traced one light path; the imaging ratio scales splats as well.
    const float imagingRatio = scene.settings().imagingRatio;
    const double lightPaths = imagingRatio > 0 ? film.meanSamplesPerPixel() * double(bounds.area()) / imagingRatio : 0.0;
    result.meanSpp = double(std::accumulate(result.distributed.rankSamples.begin(), result.distributed.rankSamples.end(), 0LL)) /
                     double(bounds.area());
    result.pixelSamples = film.sampleCounts();
    result.stoppedEarly = !complete;
    filmResults(film, lightPaths, result);
    return result;
}

}  // namespace ps
