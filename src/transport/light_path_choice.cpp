#include "transport/light_path_choice.h"

#include <algorithm>
#include <vector>

#include "render/distributed.h"
#include "render/scene.h"
#include "transport/bdpt.h"
#include "transport/renderer.h"

namespace ps {

namespace {

// Samples per pixel of each pilot. The film's half-buffers give each pixel's variance from
// two; but a path tracer's caustics are rare bright samples, and with 2 the pilot of the
// emissive mesh (bench/scenes/many-lights) judged path tracing 1.3x as efficient as BDPT where
// the render finds BDPT 2x better. With 8 it chooses BDPT there.
constexpr int kPilotSpp = 8;
// Where path tracing wins but delta lights make paths that only light subpaths reach (a point
// light seen in a mirror): those come from this share of samples, each counting 1 / share.
constexpr float kLightOnlyFloor = 0.1f;

RenderResult pilot(const Scene& scene, const BDPTIntegrator& bdpt, int threads, uint64_t seed) {
    RenderOptions o;
    o.spp = kPilotSpp;
    o.threads = threads;
    o.seed = seed ^ 0x9e3779b97f4a7c15ull;  // not the render's own samples
    o.sampler = "independent";             // half-buffers of independent samples: an unbiased variance
    o.progress = false;
    o.pixelSamples = false;
    return render(scene, bdpt, o);
}

// The pilot's relative variance (each pixel's over its squared luminance, as the benches'
// relMSE weighs errors: dark pixels count as much as bright ones, 0.01 keeps black ones
// finite) times its time: the inverse of its efficiency. `mean`: both pilots' luminance.
double varianceTime(const RenderResult& r, const std::vector<double>& mean) {
    double sum = 0;
    for (size_t i = 0; i < mean.size(); ++i) sum += r.variance.rgb[3 * i] / (mean[i] * mean[i] + 0.01);
    return sum / double(std::max<size_t>(mean.size(), 1)) * r.seconds;
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
    const RenderResult path = pilot(scene, bdpt, threads, seed);
    bdpt.setLightPathShare(1);
    const RenderResult both = pilot(scene, bdpt, threads, seed);
    std::vector<double> mean(size_t(path.image.width) * size_t(path.image.height));
    for (size_t i = 0; i < mean.size() && 3 * i + 2 < both.image.rgb.size(); ++i) {
        const Spectrum a = path.image.get(int(i % size_t(path.image.width)), int(i / size_t(path.image.width)));
        const Spectrum b = both.image.get(int(i % size_t(path.image.width)), int(i / size_t(path.image.width)));
        mean[i] = 0.5 * (double(a.luminance()) + double(b.luminance()));
    }
    c.pathVarianceTime = varianceTime(path, mean);
    c.bdptVarianceTime = varianceTime(both, mean);
    // The first process's timing decides for all, so that every process renders alike.
    std::vector<int64_t> bdptWins{c.bdptVarianceTime <= c.pathVarianceTime ? 1 : 0};
    distributed::broadcastFromRoot(bdptWins);
    c.share = bdptWins[0] ? 1.0f : c.floor;
    bdpt.setLightPathShare(c.share);
    return c;
}

}  // namespace ps
