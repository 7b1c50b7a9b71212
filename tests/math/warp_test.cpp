#include <gtest/gtest.h>

#include "math/equal_area.h"
#include "math/frame.h"
#include "math/warp.h"
#include "mc/rng.h"

using namespace ps;

TEST(Warp, ConcentricDiskStaysInDiskAndIsUniform) {
    Rng rng(1);
    int n = 200000, inner = 0;
    for (int i = 0; i < n; ++i) {
        Vec2 d = sampleConcentricDisk({rng.uniform(), rng.uniform()});
        float r2 = d.x * d.x + d.y * d.y;
        ASSERT_LE(r2, 1.0f + 1e-5f);
        if (r2 < 0.25f) ++inner;
    }
    // P(r < 1/2) = 1/4 for a uniform disk; binomial standard error.
    double p = double(inner) / n, se = std::sqrt(0.25 * 0.75 / n);
    EXPECT_NEAR(p, 0.25, 4 * se);
}

// E[f/pdf] = integral for f = cos(theta) over the hemisphere (= pi).
TEST(Warp, CosineHemisphereEstimatesProjectedSolidAngle) {
    Rng rng(2);
    int n = 100000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        Vec2 u(rng.uniform(), rng.uniform());
        Vec3 w = sampleUniformHemisphere(u);
        double v = w.z / uniformHemispherePdf();
        sum += v;
        sum2 += v * v;
        Vec3 c = sampleCosineHemisphere(u);
        ASSERT_NEAR(length(c), 1.0f, 1e-4f);
        ASSERT_GE(c.z, 0.0f);
    }
    double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, kPi, 4 * se);
}

TEST(Warp, ConeSamplesStayInCone) {
    Rng rng(3);
    float cosMax = std::cos(0.3f);
    for (int i = 0; i < 10000; ++i) {
        Vec3 w = sampleUniformCone({rng.uniform(), rng.uniform()}, cosMax);
        ASSERT_GE(w.z, cosMax - 1e-5f);
        ASSERT_NEAR(length(w), 1.0f, 1e-4f);
    }
}

TEST(Warp, TriangleBarycentricsAreUniform) {
    Rng rng(4);
    int n = 100000, nearVertex0 = 0;
    for (int i = 0; i < n; ++i) {
        Vec2 b = sampleUniformTriangle({rng.uniform(), rng.uniform()});
        ASSERT_GE(b.x, 0.0f);
        ASSERT_GE(b.y, 0.0f);
        ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
        if (b.x > 0.5f) ++nearVertex0;  // sub-triangle of area 1/4
    }
    double p = double(nearVertex0) / n;
    EXPECT_NEAR(p, 0.25, 4 * std::sqrt(0.25 * 0.75 / n));
}

TEST(EqualArea, RoundTripAndUnitLength) {
    Rng rng(5);
    for (int i = 0; i < 20000; ++i) {
        Vec2 p(rng.uniform(), rng.uniform());
        Vec3 w = equalAreaSquareToSphere(p);
        ASSERT_NEAR(length(w), 1.0f, 1e-4f);
        Vec2 q = equalAreaSphereToSquare(w);
        ASSERT_NEAR(p.x, q.x, 1e-3f);
        ASSERT_NEAR(p.y, q.y, 1e-3f);
    }
    // pbrt layout: +z at the centre, +x right-middle, +y bottom-middle (row index grows down).
    Vec2 c = equalAreaSphereToSquare({0, 0, 1});
    EXPECT_NEAR(c.x, 0.5f, 1e-5f);
    EXPECT_NEAR(c.y, 0.5f, 1e-5f);
    Vec2 px = equalAreaSphereToSquare({1, 0, 0});
    EXPECT_NEAR(px.x, 1.0f, 1e-5f);
    EXPECT_NEAR(px.y, 0.5f, 1e-5f);
    Vec2 py = equalAreaSphereToSquare({0, 1, 0});
    EXPECT_NEAR(py.x, 0.5f, 1e-5f);
    EXPECT_NEAR(py.y, 1.0f, 1e-5f);
}

// Equal area: the fraction of uniformly placed square points with z > 0 is 1/2, and
// with z > 0.5 it is 1/4 (the spherical cap's share of the sphere).
TEST(EqualArea, PreservesArea) {
    Rng rng(6);
    int n = 200000, cap = 0;
    for (int i = 0; i < n; ++i)
        if (equalAreaSquareToSphere({rng.uniform(), rng.uniform()}).z > 0.5f) ++cap;
    EXPECT_NEAR(double(cap) / n, 0.25, 4 * std::sqrt(0.25 * 0.75 / n));
}

TEST(Frame, OrthonormalAndRoundTrip) {
    Rng rng(7);
    for (int i = 0; i < 1000; ++i) {
        Vec3 n = sampleUniformSphere({rng.uniform(), rng.uniform()});
        Frame f = Frame::fromNormal(n);
        EXPECT_NEAR(dot(f.s, f.t), 0.0f, 1e-5f);
        EXPECT_NEAR(dot(f.s, f.n), 0.0f, 1e-5f);
        EXPECT_NEAR(length(f.s), 1.0f, 1e-5f);
        Vec3 v(0.3f, -0.2f, 0.9f);
        Vec3 r = f.toLocal(f.toWorld(v));
        EXPECT_NEAR(r.x, v.x, 1e-5f);
        EXPECT_NEAR(r.z, v.z, 1e-5f);
    }
}
