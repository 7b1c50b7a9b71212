// Splitting next-event estimation (--light-samples N, transport/path_tracer.h): each light
// sample counts 1/N and the MIS weights see the light technique's density N times (thesis
// §9.2's multi-sample model). Unbiased against the closed furnace's exact answer with the
// power and balance heuristics, and the same image mean as N = 1 under many lights.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "many_lights_scene.h"
#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

// Renders `text` with the path tracer taking `lightSamples` light samples per vertex (RGB).
RenderResult renderSplit(const std::string& text, int lightSamples, int spp, uint64_t seed, const std::string& mis = "") {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(text, ".", "<test>");
    auto scene = buildScene(desc, false);
    scene->settings().lightSamples = lightSamples;
    auto integrator = createIntegrator("path", *scene, mis);
    RenderOptions opts;
    opts.spp = spp;
    opts.seed = seed;
    opts.sampler = scene->settings().sampler;
    opts.progress = false;
    return render(*scene, *integrator, opts);
}

// Inside a closed sphere emitting Le with albedo 0.6, maxdepth 5: pixel = Le sum_{k<=5} 0.6^k.
// Every vertex samples the light and every BSDF direction finds it, so both MIS weights act
// at every vertex: a weight pair that does not sum to one shows at once.
TEST(LightSamples, FurnaceExactWithFourLightSamples) {
    const std::string scene = closedFurnaceScene(5, "0.5 0.25 1.0", "0.6 0.6 0.6");
    const double Le[3] = {0.5, 0.25, 1.0};
    double series = 0;
    for (int k = 0; k <= 5; ++k) series += std::pow(0.6, k);
    for (const std::string mis : {"", "balance"}) {
        const RenderResult r = renderSplit(scene, 4, 64, 11, mis);
        const RegionStats s = wholeImage(r.image);
        for (int c = 0; c < 3; ++c) {
            const double exact = Le[c] * series;
            std::printf("mis %s channel %d: %.6f +- %.6f, exact %.6f, %+.2f sigma\n", mis.empty() ? "power" : mis.c_str(),
                        c, s.mean[c], s.stdErr[c], exact, (s.mean[c] - exact) / s.stdErr[c]);
            EXPECT_NEAR(s.mean[c], exact, 4 * s.stdErr[c]);
            EXPECT_LT(4 * s.stdErr[c], 0.02 * exact) << "the test must resolve a 2% error";
        }
    }
}

// The many-light scene's image mean with 4 light samples per vertex against 1, over 8
// independent renders of each (unpaired: the two draw different paths).
TEST(LightSamples, ManyLightsAgreesWithOneLightSample) {
    const std::string scene = manyLightsScene();
    const int renders = 8;
    double m[2] = {0, 0}, m2[2] = {0, 0};
    for (int k = 0; k < 2; ++k)
        for (int i = 0; i < renders; ++i) {
            const double v = luminanceMean(renderSplit(scene, k == 0 ? 1 : 4, 64, 900 + uint64_t(i)).image);
            m[k] += v / renders;
            m2[k] += v * v / renders;
        }
    double var = 0;
    for (int k = 0; k < 2; ++k) var += std::max(0.0, m2[k] - m[k] * m[k]) * renders / (renders - 1) / renders;
    const double se = std::sqrt(var), d = m[1] - m[0];
    std::printf("N = 1: %.6f, N = 4: %.6f, difference %+.6f +- %.6f (%+.2f sigma)\n", m[0], m[1], d, se, d / se);
    EXPECT_LT(std::fabs(d), 4 * se);
    EXPECT_LT(4 * se, 0.02 * m[0]) << "the test must resolve a 2% error";
}

}  // namespace
