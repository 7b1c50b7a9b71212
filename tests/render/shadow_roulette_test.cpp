// Russian roulette on shadow rays (transport/shadow_roulette.h, --shadow-roulette): the image
// stays unbiased with an aggressive threshold, against the closed furnace's exact answer and
// against the plain estimator on a scene of many lights; and the roulette does act (shadow
// rays skipped), so that the comparisons can fail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "many_lights_scene.h"
#include "render_helpers.h"
#include "spectral_answer.h"

using namespace ps;
using namespace ps::test;

namespace {

RenderResult renderRoulette(const std::string& scene, const std::string& integrator, int spp, uint64_t seed,
                            float share) {
    RenderOptions opts;
    opts.spp = spp;
    opts.seed = seed;
    opts.shadowRoulette = share;
    return renderWith(scene, opts, integrator);
}

double skippedShare(const RenderResult& r) {
    return double(r.stats.shadowRaysSkipped) / double(std::max<uint64_t>(1, r.stats.shadowRays + r.stats.shadowRaysSkipped));
}

class ShadowRouletteFurnace : public ::testing::TestWithParam<const char*> {};

// Inside a closed sphere emitting Le with albedo 0.6, maxdepth 5: pixel = Le sum_{k<=5} 0.6^k.
// A share of 2 (light tracing, whose connections each carry a whole light path: 20) puts
// most connections' contributions below the threshold: most shadow rays are left out and the
// rest count 1/q.
TEST_P(ShadowRouletteFurnace, ExactWithMostShadowRaysLeftOut) {
    const std::string integrator = GetParam();
    const std::string scene = closedFurnaceScene(5, "0.5 0.25 1.0", "0.6 0.6 0.6");
    const int spp = integrator == "light" ? 4096 : 256;
    RenderResult r = renderRoulette(scene, integrator, spp, 7, integrator == "light" ? 20.0f : 2.0f);
    const auto exact = exactPixel(
        defaultSpectral(),
        [](double albedo, double Le) {
            double sum = 0;
            for (int k = 0; k <= 5; ++k) sum += std::pow(albedo, k);
            return Le * sum;
        },
        reflectance({0.6f, 0.6f, 0.6f}), emission({0.5f, 0.25f, 1.0f}));
    const RegionStats s = wholeImage(r.image);
    std::printf("%s: %.1f%% of shadow rays skipped\n", integrator.c_str(), 100 * skippedShare(r));
    EXPECT_GT(skippedShare(r), 0.3);
    for (int c = 0; c < 3; ++c) {
        std::printf("  channel %d: %.6f +- %.6f, exact %.6f, %+.2f sigma\n", c, s.mean[c], s.stdErr[c], exact[size_t(c)],
                    (s.mean[c] - exact[size_t(c)]) / s.stdErr[c]);
        EXPECT_NEAR(s.mean[c], exact[size_t(c)], 4 * s.stdErr[c] + 1e-4 * exact[size_t(c)]);
        EXPECT_LT(s.stdErr[c], 0.005 * exact[size_t(c)]) << "the test must resolve a 2% error";
    }
}

INSTANTIATE_TEST_SUITE_P(Integrators, ShadowRouletteFurnace, ::testing::Values("path", "bdpt", "light"));

class ShadowRouletteManyLights : public ::testing::TestWithParam<const char*> {};

// The image mean with the roulette (share 1) against every shadow ray traced, in 12 pairs of
// renders: each pair shares its seed, so both draw the same paths and differ only by the
// roulette, and the spread of the pairs' differences (independent across seeds) is the
// difference's standard error, far below either image's own.
TEST_P(ShadowRouletteManyLights, SameImageMean) {
    const std::string integrator = GetParam();
    const std::string scene = manyLightsScene();
    const int renders = 12;
    double plain = 0, sum = 0, sum2 = 0, skipped = 0;
    for (int i = 0; i < renders; ++i) {
        const RenderResult a = renderRoulette(scene, integrator, 16, 500 + uint64_t(i), 0.0f);
        const RenderResult b = renderRoulette(scene, integrator, 16, 500 + uint64_t(i), 1.0f);
        const double d = luminanceMean(b.image) - luminanceMean(a.image);
        plain += luminanceMean(a.image) / renders;
        sum += d;
        sum2 += d * d;
        skipped += skippedShare(b) / renders;
    }
    const double mean = sum / renders;
    const double se = std::sqrt(std::max(0.0, (sum2 / renders - mean * mean) * renders / (renders - 1)) / renders);
    std::printf("%s: image mean %.6f, roulette minus plain %+.6f +- %.6f (%+.2f sigma), %.1f%% skipped\n",
                integrator.c_str(), plain, mean, se, mean / se, 100 * skipped);
    EXPECT_LT(std::fabs(mean), 4 * se);
    EXPECT_GT(skipped, 0.05) << "the roulette must act for the comparison to mean anything";
    EXPECT_LT(4 * se, 0.02 * plain) << "the test must resolve a 2% error";
}

INSTANTIATE_TEST_SUITE_P(Integrators, ShadowRouletteManyLights, ::testing::Values("path", "bdpt"));

}  // namespace
