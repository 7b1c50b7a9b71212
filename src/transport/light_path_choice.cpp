#include "transport/light_path_choice.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "film/film.h"
#include "render/distributed.h"
#include "render/scene.h"
#include "transport/bdpt.h"
#include "transport/coverage.h"

namespace ps {

namespace {

// Samples per pixel of each pilot: at least two give each pixel's variance (the splatting
// film's half-buffers), and the image's mean relative variance gathers the rare bright
// samples that one pixel's pair misses when the pilot has enough of them in all: at least
// kPilotSamples, so small images take more per pixel. Each pixel's variance is taken against
// a mean those samples do not make (smoothedLuminance).
constexpr int kMinPilotSpp = 2;
constexpr double kPilotSamples = 65536;
// Where path tracing wins but delta lights make paths that only light subpaths reach (a point
// light seen in a mirror): those come from this share of samples, each counting 1 / share.
constexpr float kLightOnlyFloor = 0.1f;

int pilotSpp(const Scene& scene) {
    const double pixels = std::max(double(scene.pixelBounds().width()) * double(scene.pixelBounds().height()), 1.0);
    return std::max(kMinPilotSpp, int(std::ceil(kPilotSamples / pixels)));
}

RenderResult pilot(const Scene& scene, const BDPTIntegrator& bdpt, const RenderOptions& main, int spp) {
    RenderOptions o;
    o.spp = spp;
    o.threads = main.threads;
    o.seed = main.seed ^ 0x9e3779b97f4a7c15ull;  // not the render's own samples
    o.sampler = "independent";  // half-buffers of independent samples: an unbiased variance
    o.progress = false;
    o.cancel = main.cancel;
    return render(scene, bdpt, o);
}

// Each pixel's luminance averaged over both pilots and its 3x3 neighbourhood: the mean a
// pixel's variance is taken relative to (as the benches' relMSE weighs errors: dark pixels
// count as much as bright ones). Its own two samples would cap the relative variance near 1
// exactly where path tracing's rare caustic samples make it large.
std::vector<double> smoothedLuminance(const Image& a, const Image& b) {
    const int w = a.width, h = a.height;
    std::vector<double> out(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0;
            int n = 0;
            for (int yy = std::max(y - 1, 0); yy <= std::min(y + 1, h - 1); ++yy)
                for (int xx = std::max(x - 1, 0); xx <= std::min(x + 1, w - 1); ++xx, ++n)
                    sum += double(a.get(xx, yy).luminance()) + double(b.get(xx, yy).luminance());
            out[size_t(y) * size_t(w) + size_t(x)] = sum / (2.0 * n);
        }
    return out;
}

// The pilot's mean relative pixel variance times its time: the inverse of its efficiency.
double varianceTime(const RenderResult& r, const std::vector<double>& mean) {
    double sum = 0;
    for (size_t i = 0; i < mean.size(); ++i)
        sum += double(r.variance.rgb[3 * i]) / (mean[i] * mean[i] + Film::kRelativeEpsilon);
    return sum / double(std::max<size_t>(mean.size(), 1)) * r.seconds;
}

}  // namespace

float lightOnlyFloor(const Scene& scene) {
    // The paths only light subpaths reach (BDPTIntegrator::lightSubpathScale) leave a delta
    // light through a specular vertex (path tracing's "delta-caustic" class) or into a lens.
    bool delta = false;
    for (const auto& light : scene.lights()) delta = delta || light->isDelta();
    if (!delta) return 0;
    if (scene.camera().hasLensDisk()) return kLightOnlyFloor;
    for (const UnsampledPaths& u : unsampledPaths(scene, "path"))
        if (u.id == "delta-caustic") return kLightOnlyFloor;
    return 0;
}

LightPathChoice chooseLightPathShare(const Scene& scene, BDPTIntegrator& bdpt, const RenderOptions& options) {
    LightPathChoice c;
    const int spp = pilotSpp(scene);
    bdpt.setLightPathShare(0);
    const RenderResult path = pilot(scene, bdpt, options, spp);
    bdpt.setLightPathShare(1);
    const RenderResult both = pilot(scene, bdpt, options, spp);
    c.seconds = path.seconds + both.seconds;
    // Only the first process holds the films' sums; its judgement decides for all, so that
    // every process renders alike.
    std::vector<int64_t> bdptWins{1};
    if (path.image.width > 0 && path.variance.rgb.size() == path.image.rgb.size() &&
        both.variance.rgb.size() == path.image.rgb.size()) {
        const std::vector<double> mean = smoothedLuminance(path.image, both.image);
        c.pathVarianceTime = varianceTime(path, mean);
        c.bdptVarianceTime = varianceTime(both, mean);
        bdptWins[0] = c.bdptVarianceTime <= c.pathVarianceTime ? 1 : 0;
    }
    distributed::broadcastFromRoot(bdptWins);
    c.share = bdptWins[0] ? 1.0f : lightOnlyFloor(scene);
    bdpt.setLightPathShare(c.share);
    return c;
}

}  // namespace ps
