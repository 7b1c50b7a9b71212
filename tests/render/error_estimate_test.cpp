// The render's own error estimate (per-pixel variance of the mean) agrees with the error
// actually observed, and falls as 1/N.
#include <gtest/gtest.h>

#include <cstdio>

#include "mc/estimator.h"
#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

// Every pixel sees the same expected value (inside a closed emitting sphere), so each pixel's
// squared deviation from the image mean is an independent measurement of its variance.
std::string furnace(int resolution) {
    return R"(
    LookAt 0 0 0  0 0 1  0 1 0
    Camera "perspective" "float fov" [ 60 ]
    Film "rgb" "integer xresolution" [ )" +
           std::to_string(resolution) + R"( ] "integer yresolution" [ )" + std::to_string(resolution) + R"( ]
    PixelFilter "box"
    Sampler "independent"
    Integrator "path" "integer maxdepth" [ 5 ]
    WorldBegin
    AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
    Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
    ReverseOrientation
    Shape "sphere" "float radius" [ 1 ]
)";
}

// Per pixel: the render's variance estimate v and the observed squared deviation o (scaled by
// N / (N - 1) for the image mean's own share), and their difference.
struct PixelVariances {
    RunningStats estimated, observed, difference;
};

PixelVariances pixelVariances(const RenderResult& r) {
    const int w = r.image.width, h = r.image.height;
    const double n = double(w) * h;
    double mean = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) mean += r.image.get(x, y).luminance() / n;
    PixelVariances p;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double dev = r.image.get(x, y).luminance() - mean;
            double v = r.variance.get(x, y).g, o = dev * dev * n / (n - 1);
            p.estimated.add(v);
            p.observed.add(o);
            p.difference.add(v - o);
        }
    return p;
}

}  // namespace

// Estimated and observed variances are paired per pixel, so the standard error of their mean
// difference comes from the data (heavy tails included); it must be under 0.5% of the
// variance, so that an estimate 2% off fails.
TEST(ErrorEstimate, MatchesObservedSpreadAndFallsAsOneOverN) {
    const std::string scene = furnace(512);
    RenderResult a = renderString(scene, 4), b = renderString(scene, 16);
    PixelVariances pa = pixelVariances(a), pb = pixelVariances(b);
    double level = pa.observed.mean();
    std::printf("estimated %.6g, observed %.6g, difference %+.6g +- %.3g (%.3f%% of the variance)\n",
                pa.estimated.mean(), level, pa.difference.mean(), pa.difference.standardError(),
                100 * pa.difference.standardError() / level);
    EXPECT_NEAR(a.error.meanVariance, pa.estimated.mean(), 1e-6 * pa.estimated.mean()) << "the error estimate is the mean";
    EXPECT_LT(pa.difference.standardError(), 0.005 * level);
    EXPECT_NEAR(pa.difference.mean(), 0.0, 4 * pa.difference.standardError());

    // 4x the samples: a quarter of the variance. The two renders are independent.
    double ratio = pa.estimated.mean() / pb.estimated.mean();
    double relSE = std::hypot(pa.estimated.standardError() / pa.estimated.mean(),
                              pb.estimated.standardError() / pb.estimated.mean());
    std::printf("4 spp / 16 spp variance = %.4f +- %.4f\n", ratio, ratio * relSE);
    EXPECT_LT(relSE, 0.005);
    EXPECT_NEAR(ratio, 4.0, 4 * ratio * relSE);
    EXPECT_GT(a.efficiency, 0.0);
}
