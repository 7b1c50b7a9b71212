#include <gtest/gtest.h>

#include "camera/camera.h"
#include "film/filter.h"
#include "mc/rng.h"

#include <vector>

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

// The walk's shortcut for its own first direction (no raster test, no normalisation) must
// give pdfWe's density, for pinhole and thin lens, under a camera transform that scales
// directions (so a direction left unnormalised would show).
TEST(Camera, GeneratedRayDensityMatchesPdfWe) {
    for (float lensRadius : {0.0f, 0.1f}) {
        Camera::Params p;
        p.xRes = 48;
        p.yRes = 32;
        p.fovDeg = 50;
        p.lensRadius = lensRadius;
        p.focalDistance = 2;
        p.worldFromCamera = Transform::translate({1, 2, 3}) * Transform::rotate(30, {0, 1, 1}) *
                            Transform::scale({0.5f, 0.5f, 0.5f});
        Camera cam(p);
        Rng rng(11);
        for (int i = 0; i < 200; ++i) {
            Ray r = cam.generateRay({{rng.uniform() * 48, rng.uniform() * 32}, {rng.uniform(), rng.uniform()}});
            float pdfPos, pdfDir;
            cam.pdfWe(r, &pdfPos, &pdfDir);
            ASSERT_GT(pdfDir, 0);
            EXPECT_NEAR(cam.generatedRayPdfDir(r), pdfDir, 1e-4f * pdfDir);
        }
    }
}

// Camera samples carry weight f/pdf and pixels divide by the summed weights, so a pixel
// estimates the filter-weighted mean: sum(w g(x)) / sum(w) -> int f g / int f. Checked for
// g = x^2 + y^2 against quadrature of f, with the standard error of the ratio estimator.
static void checkFilter(const Filter& f) {
    Vec2 r = f.radius();
    double If = 0, Ifg = 0;
    const int m = 800;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
            Vec2 p(float(-r.x + 2 * r.x * (i + 0.5) / m), float(-r.y + 2 * r.y * (j + 0.5) / m));
            double v = f.evaluate(p);
            If += v;
            Ifg += v * (p.x * p.x + p.y * p.y);
        }
    double exact = Ifg / If;
    EXPECT_NEAR(f.integral(), If * 4 * r.x * r.y / (double(m) * m), 2e-3 * std::fabs(f.integral()));
    Rng rng(17);
    const int n = 400000;
    std::vector<double> w(n), g(n);
    double sw = 0, swg = 0;
    for (int i = 0; i < n; ++i) {
        FilterSample fs = f.sample({rng.uniform(), rng.uniform()});
        ASSERT_LE(std::fabs(fs.offset.x), r.x + 1e-5f);
        ASSERT_LE(std::fabs(fs.offset.y), r.y + 1e-5f);
        w[i] = fs.weight;
        g[i] = fs.offset.x * fs.offset.x + fs.offset.y * fs.offset.y;
        sw += w[i];
        swg += w[i] * g[i];
    }
    double est = swg / sw, var = 0;
    for (int i = 0; i < n; ++i) var += sqr(float(w[i] * (g[i] - est)));
    double se = std::sqrt(var) / sw;
    EXPECT_NEAR(est, exact, 4 * se + 1e-3 * exact);
}

TEST(Filter, BoxTriangleGaussianMitchellWeights) {
    checkFilter(BoxFilter({0.5f, 0.5f}));
    checkFilter(TriangleFilter({1.0f, 2.0f}));
    checkFilter(GaussianFilter({1.5f, 1.5f}, 0.5f));
    MitchellFilter mf({2, 2}, 1.f / 3, 1.f / 3);
    checkFilter(mf);
    EXPECT_NEAR(mf.integral(), 1.0, 2e-3);  // Mitchell-Netravali integrates to 1 over [-2, 2] per axis
}
