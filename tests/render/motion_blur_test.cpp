// Motion blur with pbrt-v4's semantics (TransformTimes, ActiveTransform, the camera's shutter):
// moving geometry and a moving camera against their exact time-averaged coverage. Each pixel's
// expected value is computed here in closed form (up to a fine quadrature over the pixel);
// the tolerance comes from the spread of the pixels' residuals around it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "render_helpers.h"
#include "transport/integrator.h"

using namespace ps;
using namespace ps::test;

namespace {

// 64 x 16 pixels, fov 90 (tan = 1) spanning the 16 rows: the plane z = 5 is seen over
// x in [-20, 20], y in [-5, 5]; column i covers x in [-20 + 0.625 i, -20 + 0.625 (i + 1)].
constexpr int kW = 64, kH = 16;
constexpr double kColumnWidth = 40.0 / kW;

// A white two-sided emitter behind everything (light tracing cannot see an infinite light)
// and a black quad [0, 5] x [-10, 10] in the plane z = 5, placed by `quadTransform`.
std::string quadScene(const std::string& options, const std::string& quadTransform, const std::string& camera = "",
                      int spp = 64) {
    return R"(
        LookAt 0 0 0  0 0 1  0 1 0
        )" + camera + R"(
        Camera "perspective" "float fov" 90 )" + options + R"(
        Film "rgb" "integer xresolution" 64 "integer yresolution" 16
        PixelFilter "box"
        Sampler "independent" "integer pixelsamples" )" + std::to_string(spp) + R"(
        WorldBegin
        AttributeBegin
          Material "diffuse" "rgb reflectance" [0 0 0]
          AreaLightSource "diffuse" "rgb L" [1 1 1] "bool twosided" true
          Shape "trianglemesh" "point3 P" [-70 -20 10  70 -20 10  70 20 10  -70 20 10] "integer indices" [0 1 2 0 2 3]
        AttributeEnd
        AttributeBegin
          Material "diffuse" "rgb reflectance" [0 0 0]
          )" + quadTransform + R"(
          Shape "trianglemesh" "point3 P" [0 -10 0  5 -10 0  5 10 0  0 10 0] "integer indices" [0 1 2 0 2 3]
        AttributeEnd
    )";
}

// The quad's left edge at time t is x0 + D f(t), f pbrt-v4's keyframe fraction for
// TransformTimes [T0, T1]. The fraction of the shutter [s0, s1] during which it covers x.
struct Motion {
    double x0, D, width, T0, T1, s0, s1;

    double f(double t) const { return t <= T0 ? 0 : t >= T1 ? 1 : (t - T0) / (T1 - T0); }
    // Length of {t in [s0, s1] : left edge < v} (the edge moves monotonically right).
    double timeLeftOf(double v) const {
        if (v <= x0) return 0;
        if (v > x0 + D) return s1 - s0;
        double t = T0 + (v - x0) / D * (T1 - T0);
        return std::clamp(t, s0, s1) - s0;
    }
    double coverage(double x) const { return (timeLeftOf(x) - timeLeftOf(x - width)) / (s1 - s0); }
    // Mean coverage over [xa, xb]: the integrand is piecewise linear with a few kinks, so a
    // fine midpoint rule is exact to ~1e-8.
    double meanCoverage(double xa, double xb) const {
        const int n = 4096;
        double s = 0;
        for (int k = 0; k < n; ++k) s += coverage(xa + (xb - xa) * (k + 0.5) / n);
        return s / n;
    }
};

// Pixels grouped into regions of equal expected value... or not: residuals against each
// pixel's exact value, averaged over a region, must be within 4 standard errors of zero
// (standard error from the residuals' spread). A region without noise must match to 1e-5.
struct ResidualCheck {
    double worstSigmas = 0;
    void check(const std::vector<double>& residuals, const std::string& label) {
        double s = 0, s2 = 0;
        for (double r : residuals) {
            s += r;
            s2 += r * r;
        }
        const double n = double(residuals.size());
        const double mean = s / n;
        const double sigma = std::sqrt(std::max(0.0, (s2 / n - mean * mean) / (n - 1)));
        if (sigma == 0) {
            EXPECT_NEAR(mean, 0, 1e-5) << label;
            return;
        }
        worstSigmas = std::max(worstSigmas, std::fabs(mean) / sigma);
        EXPECT_LT(std::fabs(mean), 4 * sigma) << label << ": mean residual " << mean << ", sigma " << sigma;
    }
};

// Column by column (rows are identical in expectation): image value = scale * (1 - coverage).
void expectColumns(const Image& img, const Motion& m, double scale, const char* what) {
    ResidualCheck rc;
    double maxSigma = 0;
    for (int i = 0; i < kW; ++i) {
        double xa = -20 + kColumnWidth * i;
        double expected = scale * (1 - m.meanCoverage(xa, xa + kColumnWidth));
        std::vector<double> r;
        double s = 0, s2 = 0;
        for (int y = 0; y < kH; ++y) {
            double v = img.get(i, y)[0];
            r.push_back(v - expected);
            s += v;
            s2 += v * v;
        }
        maxSigma = std::max(maxSigma, std::sqrt(std::max(0.0, (s2 / kH - s * s / (kH * kH)) / (kH - 1))));
        rc.check(r, std::string(what) + ", column " + std::to_string(i) + " (exact " + std::to_string(expected) + ")");
    }
    std::printf("  %s: largest column sigma %.4f, worst column at %.2f sigma (tolerance 4)\n", what, maxSigma,
                rc.worstSigmas);
}

}  // namespace

// A black quad moves 15 units right over the shutter (ActiveTransform EndTime Translate):
// every column sees the white backdrop for the fraction of the shutter the quad leaves it
// free, for path tracing, light tracing and BDPT.
TEST(MotionBlur, TranslatingQuadMatchesItsCoverage) {
    const std::string scene = quadScene("", "Translate -10 0 5  ActiveTransform EndTime  Translate 15 0 0  ActiveTransform All");
    const Motion m{-10, 15, 5, 0, 1, 0, 1};
    for (const char* integrator : {"path", "light", "bdpt"}) {
        RenderResult r = renderString(scene, 64, 7, 0, integrator);
        expectColumns(r.image, m, 1.0, integrator);
    }
}

// Shutter [0.25, 0.75]: only the middle half of the motion is seen, and the imaging ratio
// (close - open) halves the image. TransformTimes 0.5 1.5 with the default shutter [0, 1]:
// before 0.5 the start transform holds (pbrt-v4 clamps), so only a third of the motion.
TEST(MotionBlur, ShutterAndTransformTimesSelectTheInterval) {
    const std::string move = "Translate -10 0 5  ActiveTransform EndTime  Translate 15 0 0  ActiveTransform All";
    RenderResult a = renderString(quadScene(R"("float shutteropen" 0.25 "float shutterclose" 0.75)", move), 64, 7, 0, "path");
    expectColumns(a.image, Motion{-10, 15, 5, 0, 1, 0.25, 0.75}, 0.5, "shutter [0.25, 0.75]");
    RenderResult b = renderString("TransformTimes 0.5 1.5\n" + quadScene("", move), 64, 7, 0, "path");
    expectColumns(b.image, Motion{-10, 15, 5, 0.5, 1.5, 0, 1}, 1.0, "TransformTimes [0.5, 1.5]");
}

// A camera moving 15 units left (ActiveTransform EndTime around Camera) sees the static quad
// move 15 units right: the same coverage as the first test, also for light tracing and BDPT,
// whose splats and lens connections use the lens where it is at their path's time.
TEST(MotionBlur, MovingCameraShiftsTheScene) {
    const std::string scene = quadScene("", "Translate -10 0 5", "ActiveTransform EndTime  Translate 15 0 0  ActiveTransform All");
    // Light tracing's splats from the wide emitter are heavy-tailed at 64 spp (a column's
    // 16 rows then underestimate its spread): it takes 256.
    for (const char* integrator : {"path", "light", "bdpt"}) {
        RenderResult r = renderString(scene, std::string(integrator) == "light" ? 256 : 64, 7, 0, integrator);
        expectColumns(r.image, Motion{-10, 15, 5, 0, 1, 0, 1}, 1.0, (std::string("moving camera, ") + integrator).c_str());
    }
}

// The quadrant x, y > 0 of the plane z = 5 turns 90 degrees about the view axis. Slerp turns
// it at a constant rate, so a point at polar angle phi is covered for phi/90 of the shutter
// if phi < 90, (180 - phi)/90 if phi < 180, else never. (Interpolating the matrices instead
// would turn it at the rate of atan(t / (1 - t)): phi = 22.5 degrees covered 0.29, not 0.25.)
TEST(MotionBlur, RotatingQuadFollowsTheSlerp) {
    const int n = 32;
    std::string scene = R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" 90
        Film "rgb" "integer xresolution" 32 "integer yresolution" 32
        PixelFilter "box"
        Sampler "independent" "integer pixelsamples" 128
        WorldBegin
        LightSource "infinite" "rgb L" [1 1 1]
        Material "diffuse" "rgb reflectance" [0 0 0]
        Translate 0 0 5
        ActiveTransform EndTime
        Rotate 90 0 0 1
        ActiveTransform All
        Shape "trianglemesh" "point3 P" [0 0 0  100 0 0  100 100 0  0 100 0] "integer indices" [0 1 2 0 2 3]
    )";
    RenderResult r = renderString(scene, 128, 7, 0, "path");
    auto covered = [](double x, double y) {
        double phi = std::atan2(y, x) * 180 / M_PI;
        if (phi < 0) return 0.0;
        return phi < 90 ? phi / 90 : (180 - phi) / 90;
    };
    // Pixel (i, j) covers x in [-5 + i w, -5 + (i+1) w], y from 5 - j w down (raster y down).
    const double w = 10.0 / n;
    std::vector<std::vector<double>> bins(8);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int q = 64;
            double s = 0;
            for (int a = 0; a < q; ++a)
                for (int b = 0; b < q; ++b)
                    s += covered(-5 + w * (i + (a + 0.5) / q), 5 - w * (j + (b + 0.5) / q));
            double expected = 1 - s / (q * q);
            double phi = std::atan2(5 - w * (j + 0.5), -5 + w * (i + 0.5)) * 180 / M_PI;
            if (phi < 0) phi += 360;
            bins[size_t(phi / 45) % 8].push_back(r.image.get(i, j)[0] - expected);
        }
    ResidualCheck rc;
    for (int b = 0; b < 8; ++b) rc.check(bins[size_t(b)], "angles [" + std::to_string(45 * b) + ", " + std::to_string(45 * b + 45) + ")");
    std::printf("  worst 45-degree sector at %.2f sigma (tolerance 4)\n", rc.worstSigmas);
}

// A diffuse plane moving from z = 4 to z = 8 under a point light at the eye: a hit must be
// shaded where the plane is at the ray's time (position, normal, distance to the light), so
// a pixel's mean is (rho / pi) I / (d0 d1), the time average of 1/d(t)^2, times the cosine
// and distance factor (1 + s^2)^-3/2 of its screen-space direction s, averaged over it.
// (Shading at the start transform would double it.)
TEST(MotionBlur, MovingSurfaceIsShadedAtTheRaysTime) {
    const std::string scene = R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" 60
        Film "rgb" "integer xresolution" 16 "integer yresolution" 16
        PixelFilter "box"
        Sampler "independent" "integer pixelsamples" 256
        WorldBegin
        LightSource "point" "rgb I" [1 1 1]
        Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
        Translate 0 0 4
        ActiveTransform EndTime
        Translate 0 0 4
        ActiveTransform All
        Shape "trianglemesh" "point3 P" [-10 -10 0  10 -10 0  10 10 0  -10 10 0] "integer indices" [0 1 2 0 2 3]
    )";
    const double base = 0.5 / M_PI / (4.0 * 8.0);
    const double tanHalf = std::tan(30.0 * M_PI / 180);
    double expectedMean = 0;
    std::vector<double> expected;
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
            const int q = 16;
            double s = 0;
            for (int a = 0; a < q; ++a)
                for (int b = 0; b < q; ++b) {
                    double sx = (-1 + (i + (a + 0.5) / q) / 8) * tanHalf, sy = (1 - (j + (b + 0.5) / q) / 8) * tanHalf;
                    s += std::pow(1 + sx * sx + sy * sy, -1.5);
                }
            expected.push_back(base * s / (q * q));
            expectedMean += expected.back() / 256;
        }
    for (const char* integrator : {"path", "light", "bdpt"}) {
        RenderResult r = renderString(scene, 256, 7, 0, integrator);
        std::vector<double> res;
        for (int j = 0; j < 16; ++j)
            for (int i = 0; i < 16; ++i) res.push_back(r.image.get(i, j)[0] - expected[size_t(j * 16 + i)]);
        ResidualCheck rc;
        rc.check(res, integrator);
        RegionStats st = wholeImage(r.image);
        std::printf("  %s: image mean %.6f, exact %.6f, residual at %.2f sigma (tolerance 4)\n", integrator, st.mean[0],
                    expectedMean, rc.worstSigmas);
        EXPECT_LT(st.stdErr[0], 0.05 * expectedMean) << "too noisy to tell a 20% error";
    }
}

// Keyframes that end up equal are no motion: the scene renders as a static one, without
// drawing a time per sample (identical sample streams, so identical bits).
TEST(MotionBlur, EqualKeyframesAreStatic) {
    const std::string moving = quadScene("", "Translate -10 0 5  ActiveTransform EndTime  Translate 15 0 0  ActiveTransform All");
    const std::string still = quadScene("", "Translate -10 0 5  ActiveTransform StartTime  Translate 0 0 0  ActiveTransform All");
    const std::string plain = quadScene("", "Translate -10 0 5");
    EXPECT_TRUE(buildScene(parseSceneString(moving, ".", "<test>"))->hasMotion());
    EXPECT_FALSE(buildScene(parseSceneString(still, ".", "<test>"))->hasMotion());
    RenderResult a = renderString(still, 4, 7, 1, "bdpt"), b = renderString(plain, 4, 7, 1, "bdpt");
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) ASSERT_EQ(a.image.get(x, y)[0], b.image.get(x, y)[0]) << x << ", " << y;
}
