// A scene whose every pixel is known exactly, for checking the normalisation of the images
// the command writes (early stops, options): a diffuse sphere of albedo 0.5 under a uniform
// white sky of radiance 1. A convex object never sees itself, so every point of the sphere
// reflects exactly 0.5 at any path depth >= 1; the sky is exactly 1. With a box filter a
// pixel is the mean over its own square, so only the pixels the silhouette crosses are
// unknown, and (one splat per light path, the sphere being met at most once) pixels are
// independent estimates: their spread measures the standard error of the class mean.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "image/image.h"

namespace ps::test {

inline const char* kSkyScene = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 24 ] "string filename" [ "sky.exr" ]
PixelFilter "box"
Sampler "independent" "integer pixelsamples" [ 4 ]
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
Shape "sphere" "float radius" [ 1 ]
)";

// kSkyScene's exact pixel (x, y): 0.5 on the sphere, 1 on the sky, NaN where the silhouette
// is within a pixel of the pixel's centre. The sphere (radius 1, 5 away) subtends
// asin(1/5) from the axis; fov 30 spans the 24 rows.
inline double exactSkyPixel(int x, int y) {
    const double radius = 12 * std::tan(std::asin(0.2)) / std::tan(15 * M_PI / 180);  // 9.14 pixels
    const double d = std::hypot(x + 0.5 - 16, y + 0.5 - 12);
    if (d + 1 < radius) return 0.5;
    if (d - 1 > radius) return 1.0;
    return NAN;
}

// Per class (sphere, sky): the mean of (pixel - exact) over its pixels must be within 4
// standard errors (from the pixels' spread; plus 1e-5 for float rounding), and that bound
// must be below 1% of the exact value, so that a normalisation 2% off fails. Light tracing
// cannot image the sky it sees directly (README): pass sky = 0 for it.
inline void expectExactSkyImage(const Image& img, const std::string& what, double sky = 1.0) {
    ASSERT_EQ(img.width, 32);
    ASSERT_EQ(img.height, 24);
    for (bool sphere : {true, false}) {
        const double exact = sphere ? 0.5 : sky;
        double s = 0, s2 = 0;
        int n = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                if (exactSkyPixel(x, y) != (sphere ? 0.5 : 1.0)) continue;
                Spectrum v = img.get(x, y);
                double d = (double(v.r) + v.g + v.b) / 3 - exact;
                s += d;
                s2 += d * d;
                ++n;
            }
        const double mean = s / n, se = std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1));
        const double bound = 4 * se + 1e-5;
        std::printf("%s, %s: %d pixels, mean %.6f (exact %.1f), sigma %.2e (%.3f%% of 0.5)\n", what.c_str(),
                    sphere ? "sphere" : "sky", n, exact + mean, exact, se, 100 * se / 0.5);
        EXPECT_LT(std::fabs(mean), bound) << what << ": mean " << exact + mean << ", exact " << exact << ", sigma " << se;
        if (exact > 0) {
            EXPECT_LT(bound, 0.01 * exact) << what << ": too noisy to resolve a 2% error";
        }
    }
}

}  // namespace ps::test
