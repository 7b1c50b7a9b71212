#include "transport/light_path_choice.h"

#include "render/distributed.h"
#include "render/scene.h"
#include "transport/bdpt.h"
#include "transport/renderer.h"

namespace ps {

namespace {

// Two samples per pixel: the film's half-buffers then give each pixel's variance, and the
// image's mean of it is steady over the thousands of pixels a pilot covers.
constexpr int kPilotSpp = 2;
// Where path tracing wins but delta lights make paths that only light subpaths reach (a point
// light seen in a mirror): those come from this share of samples, each counting 1 / share.
constexpr float kLightOnlyFloor = 0.1f;

// The pilot's mean pixel variance times its time: the inverse of its efficiency.
double varianceTime(const Scene& scene, const BDPTIntegrator& bdpt, int threads, uint64_t seed) {
    RenderOptions o;
    o.spp = kPilotSpp;
    o.threads = threads;
    o.seed = seed ^ 0x9e3779b97f4a7c15ull;  // not the render's own samples
    o.sampler = "independent";             // half-buffers of independent samples: an unbiased variance
    o.progress = false;
    o.varianceImage = false;
    o.pixelSamples = false;
    const RenderResult r = render(scene, bdpt, o);
    return r.error.meanVariance * r.seconds;
}

}  // namespace

float lightOnlyFloor(const Scene& scene) {
    for (const auto& light : scene.lights())
        if (light->isDelta()) return kLightOnlyFloor;
    return 0;
}

LightPathChoice chooseLightPathShare(const Scene& scene, BDPTIntegrator& bdpt, int threads, uint64_t seed) {
    LightPathChoice c;
    c.pilotSpp = kPilotSpp;
    c.floor = lightOnlyFloor(scene);
    bdpt.setLightPathShare(0);
    c.pathVarianceTime = varianceTime(scene, bdpt, threads, seed);
    bdpt.setLightPathShare(1);
    c.bdptVarianceTime = varianceTime(scene, bdpt, threads, seed);
    // The first process's timing decides for all, so that every process renders alike.
    std::vector<int64_t> bdptWins{c.bdptVarianceTime <= c.pathVarianceTime ? 1 : 0};
    distributed::broadcastFromRoot(bdptWins);
    c.share = bdptWins[0] ? 1.0f : c.floor;
    bdpt.setLightPathShare(c.share);
    return c;
}

}  // namespace ps
