// Adaptive sampling in the renderer (thesis ch. 2, §5.3.1): the two-stage scheme is
// unbiased, the sequential rule is not, and both put samples where the variance is.
// Tolerances come from the spread measured across independent renders.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "render_helpers.h"
#include "transport/sample_allocation.h"

using namespace ps;
using namespace ps::test;

namespace {

// An orthographic view of a grid of tiny emitting spheres, one centred in each pixel and
// covering a fraction kHit of it, before a uniform background. A pixel sample sees the
// sphere (radiance kLe) with probability kHit, else the background: rare large values, with
// the exact pixel value kHit * kLe + (1 - kHit) * kBg. With `leftHalfOnly` the right half
// has only the background (zero variance).
constexpr int kRes = 64;
constexpr double kHit = 1.0 / 16, kLe = 16, kBg = 0.25;
const double kExact = kHit * kLe + (1 - kHit) * kBg;

std::string rareValueScene(bool leftHalfOnly = false) {
    const double pixel = 2.0 / kRes;  // screen window [-1, 1]^2
    const double radius = std::sqrt(kHit * pixel * pixel / M_PI);
    std::ostringstream s;
    s << "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"orthographic\"\n"
      << "Film \"rgb\" \"integer xresolution\" [ " << kRes << " ] \"integer yresolution\" [ " << kRes << " ]\n"
      << "PixelFilter \"box\"\nSampler \"independent\"\nIntegrator \"path\" \"integer maxdepth\" [ 0 ]\n"
      << "WorldBegin\nLightSource \"infinite\" \"rgb L\" [ " << kBg << " " << kBg << " " << kBg << " ]\n"
      << "Material \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n"
      << "AreaLightSource \"diffuse\" \"rgb L\" [ " << kLe << " " << kLe << " " << kLe << " ]\n";
    s.precision(9);
    for (int j = 0; j < kRes; ++j)
        for (int i = 0; i < kRes; ++i) {
            double x = -1 + (i + 0.5) * pixel, y = -1 + (j + 0.5) * pixel;
            if (leftHalfOnly && x > 0) continue;  // the image's left half: camera x points to -world x
            s << "AttributeBegin\nTranslate " << x << " " << y << " 5\nShape \"sphere\" \"float radius\" [ " << radius
              << " ]\nAttributeEnd\n";
        }
    return s.str();
}

const std::string kFurnace = closedFurnaceScene(5, "1 1 1", "0.6 0.6 0.6");
const double kFurnaceExact = (1 - std::pow(0.6, 6)) / 0.4;  // sum_{k=0..5} 0.6^k

// Mean luminance of the image over `renders` independent renders, with its standard error
// from the spread across renders.
struct Spread {
    double mean = 0, stdErr = 0;
};
Spread meanOverRenders(const std::string& scene, AdaptiveMode mode, int spp, int renders) {
    double s = 0, s2 = 0;
    for (int k = 0; k < renders; ++k) {
        RenderOptions o;
        o.spp = spp;
        o.seed = 1000 + uint64_t(k);
        o.adaptive = mode;
        RegionStats r = wholeImage(renderWith(scene, o).image);
        double y = 0.2126 * r.mean[0] + 0.7152 * r.mean[1] + 0.0722 * r.mean[2];
        s += y;
        s2 += y * y;
    }
    Spread out;
    out.mean = s / renders;
    out.stdErr = std::sqrt(std::max(0.0, (s2 / renders - out.mean * out.mean) / (renders - 1)));
    return out;
}

double meanSamples(const RenderResult& r, int x0, int x1) {
    double s = 0;
    int n = 0;
    for (int y = 0; y < r.image.height; ++y)
        for (int x = x0; x < x1; ++x, ++n) s += r.pixelSamples[size_t(y) * r.image.width + x];
    return s / n;
}

}  // namespace

TEST(SampleAllocation, ProportionalWithMinimumAndExactTotal) {
    std::vector<int> a = proportionalAllocation({0, 1, 3, 0}, 20, 1);
    EXPECT_EQ(a[0], 1);
    EXPECT_EQ(a[3], 1);
    EXPECT_EQ(a[1] + a[2], 18);
    EXPECT_EQ(a[2] - 1, 3 * (a[1] - 1));  // the samples beyond the minimum are proportional
    std::vector<int> u = proportionalAllocation({0, 0, 0}, 10, 1);  // no information: uniform
    EXPECT_EQ(u[0] + u[1] + u[2], 10);
    EXPECT_LE(std::abs(u[0] - u[2]), 1);
    EXPECT_EQ(largestK({0.5, 2, 2, 1}, 2), (std::vector<size_t>{1, 2}));
}

// The uniform render of the rare-value scene agrees with its exact value: the scene is what
// the tests below assume.
TEST(Adaptive, RareValueSceneIsExactWithUniformSampling) {
    Spread u = meanOverRenders(rareValueScene(), AdaptiveMode::None, 16, 8);
    std::printf("rare values, uniform: %.5f +- %.5f (%.2f%%), exact %.5f\n", u.mean, u.stdErr, 100 * u.stdErr / kExact, kExact);
    EXPECT_NEAR(u.mean, kExact, 4 * u.stdErr) << "exact " << kExact;
    EXPECT_LT(u.stdErr, 0.005 * kExact);  // a 2% error fails
}

TEST(Adaptive, TwoStageIsUnbiasedOnTheClosedFurnace) {
    Spread t = meanOverRenders(kFurnace, AdaptiveMode::TwoStage, 32, 12);
    std::printf("two-stage furnace: %.5f +- %.5f, exact %.5f\n", t.mean, t.stdErr, kFurnaceExact);
    EXPECT_NEAR(t.mean, kFurnaceExact, 4 * t.stdErr + 1e-4 * kFurnaceExact);
    EXPECT_LT(t.stdErr, 0.005 * kFurnaceExact);  // a 2% error fails
}

// The sequential rule never refines a pixel whose first samples all missed the rare bright
// sphere (its estimated variance is zero), so such pixels stay at the background: biased
// low, far outside the band; the two-stage scheme, on the same scene and budget, is not.
TEST(Adaptive, SequentialIsBiasedWhereTwoStageIsNot) {
    Spread seq = meanOverRenders(rareValueScene(), AdaptiveMode::Sequential, 16, 12);
    Spread two = meanOverRenders(rareValueScene(), AdaptiveMode::TwoStage, 16, 12);
    std::printf("rare values, exact %.4f: sequential %.4f +- %.4f (%.1f sigma), two-stage %.4f +- %.4f (%.1f sigma)\n",
                kExact, seq.mean, seq.stdErr, (seq.mean - kExact) / seq.stdErr, two.mean, two.stdErr,
                (two.mean - kExact) / two.stdErr);
    EXPECT_NEAR(two.mean, kExact, 4 * two.stdErr);
    EXPECT_LT(two.stdErr, 0.005 * kExact);  // a 2% error of the two-stage scheme fails
    EXPECT_LT(seq.mean, kExact - 4 * seq.stdErr);
    EXPECT_LT(seq.mean, kExact - 4 * two.stdErr);  // also outside two-stage's band
}

// Half the image is a constant background: both schemes spend the budget on the other half.
TEST(Adaptive, SamplesGoWhereTheVarianceIs) {
    for (AdaptiveMode mode : {AdaptiveMode::Sequential, AdaptiveMode::TwoStage}) {
        RenderOptions o;
        o.spp = 32;
        o.seed = 3;
        o.adaptive = mode;
        RenderResult r = renderWith(rareValueScene(true), o);
        double left = meanSamples(r, 0, kRes / 2), right = meanSamples(r, kRes / 2, kRes);
        std::printf("%s: left (noisy) %.1f spp, right (constant) %.1f spp, mean %.2f\n",
                    mode == AdaptiveMode::Sequential ? "sequential" : "two-stage", left, right, r.meanSpp);
        EXPECT_GT(left, 3 * right);
        EXPECT_NEAR(r.meanSpp, 32, 1.0);  // the budget is the average
    }
}

TEST(Adaptive, DeterministicForSeedAndThreads) {
    for (AdaptiveMode mode : {AdaptiveMode::Sequential, AdaptiveMode::TwoStage}) {
        RenderOptions o;
        o.spp = 16;
        o.seed = 5;
        o.threads = 2;
        o.adaptive = mode;
        RenderResult a = renderWith(kFurnace, o), b = renderWith(kFurnace, o);
        EXPECT_EQ(a.image.rgb, b.image.rgb);
        EXPECT_EQ(a.pixelSamples, b.pixelSamples);
    }
}

// A time budget turns into a sample budget, and the image is complete and correctly
// normalised: exact within 4 sigma (the pixels are independent estimates of one value), with
// sigma small enough that a 2% error fails. (How close to the limit it ends is a matter of
// timing, which is no test on a loaded machine.)
TEST(Adaptive, TimeBudget) {
    for (AdaptiveMode mode : {AdaptiveMode::Sequential, AdaptiveMode::TwoStage}) {
        RenderOptions o;
        o.spp = 1 << 20;
        o.timeLimit = 0.5;
        o.adaptive = mode;
        RenderResult r = renderWith(kFurnace, o);
        EXPECT_GT(r.meanSpp, 8);
        for (int n : r.pixelSamples) ASSERT_GT(n, 0);
        RegionStats s = wholeImage(r.image);
        std::printf("%s, time budget: %.0f spp, %.5f +- %.5f, exact %.5f\n",
                    mode == AdaptiveMode::Sequential ? "sequential" : "two-stage", r.meanSpp, s.mean[0], s.stdErr[0],
                    kFurnaceExact);
        EXPECT_LT(s.stdErr[0], 0.005 * kFurnaceExact);
        EXPECT_NEAR(s.mean[0], kFurnaceExact, 4 * s.stdErr[0] + 1e-4 * kFurnaceExact);
    }
}

TEST(Adaptive, RejectsSplattingIntegrators) {
    for (const char* integrator : {"light", "bdpt"}) {
        RenderOptions o;
        o.spp = 4;
        o.adaptive = AdaptiveMode::TwoStage;
        EXPECT_THROW(renderWith(kFurnace, o, integrator), InputError) << integrator;
    }
}
