#include "transport/renderer.h"

#include <algorithm>

#include <tbb/task_arena.h>

#include "mc/estimator.h"
#include "mc/sampler.h"

#include "util/error.h"
#include "util/memory_limit.h"

#include "transport/mlt/metropolis.h"
#include "transport/render_monitor.h"
#include "transport/sample_passes.h"

namespace ps {

namespace {

// Passes of growing size: an early stop leaves every pixel with a similar count, and each
// pixel is normalised by its own weights, so the image stays unbiased.
bool renderUniform(SamplePasses& passes, Film& film, int spp) {
    int s0 = 0, pass = 1;
    while (s0 < spp) {
        int s1 = std::min(spp, s0 + pass);
        if (!passes.run(film, [&](size_t) { return SampleSpan{s0, s1}; })) return false;
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

}  // namespace

void filmResults(const Film& film, double lightPaths, const RenderSettings& settings, RenderResult& result) {
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
    result.variance = film.varianceImage(lightPaths);
    result.rejectedSamples = film.rejectedSamples();
    result.error = film.errorEstimate(lightPaths);
    result.efficiency = efficiency(result.error.meanRelativeVariance, result.seconds);
}

RenderResult render(const Scene& scene, const Integrator& integrator, const RenderOptions& options) {
    if (options.adaptive != AdaptiveMode::None && integrator.splats())
        throw InputError("adaptive sampling needs an integrator whose pixels come from their own samples "
                         "(path); light tracing, BDPT and Metropolis splat onto the whole film");
    requireFilmMemory(scene, integrator, options);
    // Markov chains have their own driver: a chain is not a per-camera-ray estimate.
    if (auto* mlt = dynamic_cast<const MetropolisIntegrator*>(&integrator)) return renderMetropolis(scene, *mlt, options);
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
    {
        Monitor monitor(options.progress, options.timeLimit, options.cancel, stop, samplesDone, bounds.area() * spp);
        switch (options.adaptive) {
            case AdaptiveMode::None: complete = renderUniform(passes, film, spp); break;
            case AdaptiveMode::Sequential: complete = renderSequential(passes, film, monitor, spp); break;
            case AdaptiveMode::TwoStage: complete = renderTwoStage(passes, film, monitor, spp); break;
        }
        result.seconds = monitor.elapsed();
    }
    result.stats = passes.stats();
    // Every camera sample traced one light path; the imaging ratio scales splats as well.
    const float imagingRatio = scene.settings().imagingRatio;
    const double lightPaths = imagingRatio > 0 ? film.meanSamplesPerPixel() * double(bounds.area()) / imagingRatio : 0.0;
    result.meanSpp = double(passes.samplesDone()) / double(bounds.area());
    result.pixelSamples = film.sampleCounts();
    result.stoppedEarly = !complete;
    filmResults(film, lightPaths, scene.settings(), result);
    return result;
}

}  // namespace ps
