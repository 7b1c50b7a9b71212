#include <gtest/gtest.h>

#include "camera/camera.h"
#include "film/filter.h"
#include "mc/rng.h"

using namespace ps;

// pbrt-v4 raster conventions: the pixel centre of the image maps to the viewing axis, row 0
// is the top, and fov spans the shorter axis.
TEST(Camera, PerspectiveRasterConventions) {
    Camera::Params p;
    p.xRes = 200;
    p.yRes = 100;
    p.fovDeg = 90;
    Camera cam(p);
    Ray centre = cam.generateRay({{100, 50}, {0.5f, 0.5f}});
    EXPECT_NEAR(centre.d.z, 1.0f, 1e-6f);
    // Top edge, middle column: 45 degrees up (fov spans y, the shorter axis).
    Ray top = cam.generateRay({{100, 0}, {0.5f, 0.5f}});
    EXPECT_NEAR(top.d.y / top.d.z, 1.0f, 1e-5f);
    EXPECT_NEAR(top.d.x, 0.0f, 1e-6f);
    // Right edge: x = aspect * tan(45) = 2.
    Ray right = cam.generateRay({{200, 50}, {0.5f, 0.5f}});
    EXPECT_NEAR(right.d.x / right.d.z, 2.0f, 1e-5f);
}

TEST(Camera, ThinLensFocusesOnThePlane) {
    Camera::Params p;
    p.xRes = p.yRes = 64;
    p.fovDeg = 40;
    p.lensRadius = 0.2f;
    p.focalDistance = 3;
    Camera cam(p);
    Rng rng(3);
    // Every lens sample through the same film point meets at the same point on z = 3.
    Vec3 first;
    for (int i = 0; i < 50; ++i) {
        Ray r = cam.generateRay({{10.3f, 40.7f}, {rng.uniform(), rng.uniform()}});
        float t = (3 - r.o.z) / r.d.z;
        Vec3 q = r.o + r.d * t;
        if (i == 0) first = q;
        EXPECT_NEAR(q.x, first.x, 1e-4f);
        EXPECT_NEAR(q.y, first.y, 1e-4f);
    }
}

TEST(Camera, Orthographic) {
    Camera::Params p;
    p.projection = Camera::Projection::Orthographic;
    p.xRes = p.yRes = 10;
    Camera cam(p);
    Ray r = cam.generateRay({{0, 0}, {0.5f, 0.5f}});
    EXPECT_NEAR(r.o.x, -1.0f, 1e-6f);
    EXPECT_NEAR(r.o.y, 1.0f, 1e-6f);
    EXPECT_NEAR(r.d.z, 1.0f, 1e-6f);
}

// Sampled offsets with weight f/pdf: E[weight] = integral of f, and E[weight * g(offset)]
// = integral of f*g, for every filter.
static void checkFilter(const Filter& f, double exactIntegral) {
    Rng rng(17);
    int n = 400000;
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        FilterSample fs = f.sample({rng.uniform(), rng.uniform()});
        ASSERT_LE(std::fabs(fs.offset.x), f.radius().x + 1e-5f);
        ASSERT_LE(std::fabs(fs.offset.y), f.radius().y + 1e-5f);
        s += fs.weight;
        s2 += double(fs.weight) * fs.weight;
    }
    double mean = s / n, se = std::sqrt(std::max(0.0, s2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, exactIntegral, 4 * se + 2e-3 * std::fabs(exactIntegral));
    EXPECT_NEAR(f.integral(), exactIntegral, 2e-3 * std::fabs(exactIntegral));
}

TEST(Filter, BoxTriangleGaussianMitchellWeights) {
    checkFilter(BoxFilter({0.5f, 0.5f}), 1.0);
    checkFilter(TriangleFilter({1.0f, 2.0f}), 1.0 * 4.0);
    // Truncated, shifted Gaussian: integral of [G(x) - G(r)]+ per axis, by quadrature.
    GaussianFilter g({1.5f, 1.5f}, 0.5f);
    double oneD = 0;
    int m = 200000;
    for (int i = 0; i < m; ++i) {
        double x = -1.5 + 3.0 * (i + 0.5) / m;
        auto G = [](double v) { return std::exp(-v * v / 0.5) / std::sqrt(2 * M_PI * 0.25); };
        oneD += std::max(0.0, G(x) - G(1.5)) * 3.0 / m;
    }
    checkFilter(g, oneD * oneD);
    MitchellFilter mf({2, 2}, 1.f / 3, 1.f / 3);
    checkFilter(mf, 1.0);  // Mitchell-Netravali integrates to 1 over [-2, 2] per axis
}
