// The variance image (--aov variance): each pixel's estimated variance of its mean
// luminance agrees with the variance observed across independent renders, for a camera
// integrator (the pixel's own samples) and a splatting one (the two half-buffers).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

struct VarianceCheck {
    double ratio = 0;        // observed across renders / mean of the variance images
    double ratioStdErr = 0;  // from the per-pixel scatter (pixels are independent)
    double meanAov = 0;
};

// K renders: per pixel, the sample variance of its luminance across renders (a) and the
// mean of its variance-image values (b). The ratio sum a / sum b is 1 in expectation; its
// standard error, sqrt(sum_p (a_p - r b_p)^2) / sum b (ratio-estimator linearisation), is
// measured from the same data.
VarianceCheck compareWithRenders(const std::string& scene, const std::string& integrator, int spp, int renders) {
    std::vector<double> s, s2, aov;
    for (int k = 0; k < renders; ++k) {
        RenderResult r = renderString(scene, spp, 500 + uint64_t(k), 0, integrator);
        size_t n = size_t(r.image.width) * r.image.height;
        s.resize(n, 0.0);
        s2.resize(n, 0.0);
        aov.resize(n, 0.0);
        for (int y = 0; y < r.image.height; ++y)
            for (int x = 0; x < r.image.width; ++x) {
                size_t i = size_t(y) * r.image.width + x;
                double l = r.image.get(x, y).luminance();
                s[i] += l;
                s2[i] += l * l;
                aov[i] += r.variance.get(x, y).g / renders;
                EXPECT_EQ(r.variance.get(x, y).r, r.variance.get(x, y).g);  // grey: luminance
            }
    }
    std::vector<double> a(s.size());
    double sa = 0, sb = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        double m = s[i] / renders;
        a[i] = std::max(0.0, (s2[i] - renders * m * m) / (renders - 1));
        sa += a[i];
        sb += aov[i];
    }
    VarianceCheck c;
    c.ratio = sa / sb;
    double e2 = 0;
    for (size_t i = 0; i < s.size(); ++i) e2 += (a[i] - c.ratio * aov[i]) * (a[i] - c.ratio * aov[i]);
    c.ratioStdErr = std::sqrt(e2) / sb;
    c.meanAov = sb / double(s.size());
    return c;
}

const char* kFurnace = R"(
    LookAt 0 0 0  0 0 1  0 1 0
    Camera "perspective" "float fov" [ 60 ]
    Film "rgb" "integer xresolution" [ 64 ] "integer yresolution" [ 64 ]
    PixelFilter "box"
    Sampler "independent"
    Integrator "path" "integer maxdepth" [ 2 ]
    WorldBegin
    AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
    Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
    ReverseOrientation
    Shape "sphere" "float radius" [ 1 ]
)";

// Half the view is a lit diffuse sphere (noisy), the rest a uniform sky (exact): the
// per-pixel variances differ, so the comparison is pixel by pixel, not only on average.
const char* kSphereUnderSky = R"(
    LookAt 0 0 5  1 0 0  0 1 0
    Camera "perspective" "float fov" [ 30 ]
    Film "rgb" "integer xresolution" [ 112 ] "integer yresolution" [ 112 ]
    PixelFilter "box"
    Sampler "independent"
    Integrator "path" "integer maxdepth" [ 3 ]
    WorldBegin
    LightSource "infinite" "rgb L" [ 0.5 0.5 0.5 ]
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 40 40 40 ]
      Translate 0 4 2
      Shape "sphere" "float radius" [ 0.3 ]
    AttributeEnd
    Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
    Shape "sphere" "float radius" [ 1 ]
)";

void expectRatioNearOne(const VarianceCheck& c, const char* what) {
    std::printf("%s: observed / estimated variance = %.3f +- %.3f (mean estimate %.4g)\n", what, c.ratio,
                c.ratioStdErr, c.meanAov);
    EXPECT_NEAR(c.ratio, 1.0, 4 * c.ratioStdErr) << what;
    EXPECT_LT(c.ratioStdErr, 0.005) << what;  // the test must be able to detect a 2% error
    EXPECT_GT(c.meanAov, 0.0) << what;
}

}  // namespace

TEST(VarianceAov, PathTracerPixelVarianceMatchesRenders) {
    expectRatioNearOne(compareWithRenders(kSphereUnderSky, "path", 8, 64), "path, sphere under sky");
}

TEST(VarianceAov, LightTracerHalfBufferVarianceMatchesRenders) {
    expectRatioNearOne(compareWithRenders(kFurnace, "light", 4, 64), "light, closed furnace");
}

// It is the quantity the render's error estimate averages.
TEST(VarianceAov, MeanIsTheErrorEstimate) {
    RenderResult r = renderString(kFurnace, 16, 9, 0, "path");
    double sum = 0;
    for (int y = 0; y < r.variance.height; ++y)
        for (int x = 0; x < r.variance.width; ++x) sum += r.variance.get(x, y).g;
    EXPECT_NEAR(sum / (r.variance.width * r.variance.height), r.error.meanVariance, 1e-6 * r.error.meanVariance);
}
