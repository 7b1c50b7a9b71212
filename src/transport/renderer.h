// Drives an integrator over the image: tiles in parallel (oneTBB), sample passes, time
// budget and cancellation, progress on stderr, statistics.
#pragma once
#include <atomic>
#include <cstdint>
#include <string>
#include "film/film.h"
#include "image/image.h"
#include "render/scene.h"
#include "transport/integrator.h"

namespace ps {

struct RenderOptions {
    int spp = 16;
    double timeLimit = 0;        // seconds; 0 = none
    int threads = 0;             // 0 = all cores
    uint64_t seed = 0;
    std::string sampler = "sobol";  // see createSampler
    bool progress = true;        // progress bar on stderr
    const std::atomic<bool>* cancel = nullptr;  // set asynchronously (Ctrl-C) to stop early
};

struct RenderResult {
    Image image;                 // the crop region, weighted mean per pixel
    double seconds = 0;
    double meanSpp = 0;          // samples actually taken per pixel, on average
    double lightPaths = 0;       // splat normalisation: light paths traced / imaging ratio
    int targetSpp = 0;
    bool stoppedEarly = false;   // time budget or cancellation
    PathStats stats;
    long long rejectedSamples = 0;
    Film::ErrorEstimate error;  // per-pixel variance of the estimate, averaged over the image
    // Efficiency 1/(V T) with V the mean relative variance and T the render time (thesis eq. 2.26).
    double efficiency = 0;
};

RenderResult render(const Scene& scene, const Integrator& integrator, const RenderOptions& options);

}  // namespace ps
