// Shared helpers for statistical render tests: render a scene string and summarise a
// region of pixels. In a region where the exact image is constant, pixels are independent
// estimates of the same value, so their spread gives the standard error of the mean.
#pragma once
#include <cmath>
#include <string>

#include "mc/sampler.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/renderer.h"
#include "util/error.h"

namespace ps::test {

inline RenderResult renderString(const std::string& text, int spp, uint64_t seed = 7, int threads = 0,
                                 const std::string& integrator = "") {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(text, ".", "<test>");
    auto scene = buildScene(desc);
    if (!integrator.empty()) scene->settings().integrator = integrator;
    auto integ = createIntegrator(scene->settings().integrator, *scene);
    RenderOptions opts;
    opts.spp = spp;
    opts.seed = seed;
    opts.sampler = scene->settings().sampler;
    opts.threads = threads;
    opts.progress = false;
    return render(*scene, *integ, opts);
}

struct RegionStats {
    double mean[3] = {0, 0, 0};
    double stdErr[3] = {0, 0, 0};
    int n = 0;
};

inline RegionStats regionStats(const Image& img, int x0, int x1, int y0, int y1) {
    RegionStats r;
    double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            Spectrum v = img.get(x, y);
            for (int c = 0; c < 3; ++c) {
                s[c] += v[c];
                s2[c] += double(v[c]) * v[c];
            }
            ++r.n;
        }
    for (int c = 0; c < 3; ++c) {
        r.mean[c] = s[c] / r.n;
        double var = std::max(0.0, (s2[c] / r.n - r.mean[c] * r.mean[c]) * r.n / (r.n - 1));
        r.stdErr[c] = std::sqrt(var / r.n);
    }
    return r;
}

inline RegionStats wholeImage(const Image& img) { return regionStats(img, 0, img.width, 0, img.height); }

}  // namespace ps::test
