// Shape "cylinder" against geometry built in the test: rays aimed at known points of the
// wall must find them, with pbrt-v4's normal, (u, v) and area.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "geometry/interaction.h"
#include "geometry/quadric.h"

using namespace ps;

namespace {

Vec3 wallPoint(float r, float phi, float z) { return Vec3(r * std::cos(phi), r * std::sin(phi), z); }

}  // namespace

// A ray from outside the infinite cylinder that enters it at p (dot(d, n) < 0) meets the wall
// first at p; when p lies outside the part (z or phi), the exit point q on the same chord (the
// reflection of p across the chord's midpoint) is next, if it lies inside the part.
TEST(Cylinder, IntersectionsAtConstructedPoints) {
    const float r = 0.7f, zMin = -0.4f, zMax = 1.3f, phiMaxDeg = 250;
    const float phiMax = phiMaxDeg * kPi / 180;
    Cylinder cyl(Transform(), false, r, zMax, zMin, phiMaxDeg);  // zmin > zmax: swapped, as pbrt-v4
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(0, 1);
    int hits = 0, exits = 0, misses = 0;
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        float phi = 2 * kPi * U(rng), z = -1 + 3 * U(rng);
        Vec3 p = wallPoint(r, phi, z), n(std::cos(phi), std::sin(phi), 0);
        Vec3 d = normalize(Vec3(U(rng) * 2 - 1, U(rng) * 2 - 1, U(rng) * 2 - 1));
        if (dot(d, n) > -0.05f) continue;  // entering, not grazing
        float t0 = 0.5f + 2 * U(rng);
        Vec3 o = p - d * t0;
        if (o.x * o.x + o.y * o.y <= r * r * 1.01f) continue;
        auto inPart = [&](Vec3 q) {
            float a = std::atan2(q.y, q.x);
            if (a < 0) a += 2 * kPi;
            return q.z >= zMin && q.z <= zMax && a <= phiMax;
        };
        float expected = -1;
        if (inPart(p)) {
            expected = t0;
            ++hits;
        } else {
            Vec3 dxy(d.x, d.y, 0);
            float tq = -2 * dot(Vec3(p.x, p.y, 0), dxy) / dot(dxy, dxy);
            Vec3 q = p + d * tq;
            if (inPart(q)) {
                expected = t0 + tq;
                ++exits;
            } else {
                ++misses;
            }
        }
        float t = cyl.intersectObject(o, d, 0, 1e30f);
        if (expected < 0) {
            EXPECT_LT(t, 0) << "ray " << i;
            continue;
        }
        worst = std::max(worst, double(std::fabs(t - expected)));
        ASSERT_NEAR(t, expected, 1e-4f) << "ray " << i;
        EXPECT_LT(cyl.intersectObject(o, d, 0, expected * 0.999f), 0) << "tMax must cut the hit off";
    }
    std::printf("  %d entry hits, %d hits on the far wall, %d misses; largest |t - t_exact| %.2g\n", hits, exits, misses, worst);
    EXPECT_GT(hits, 1000);
    EXPECT_GT(exits, 500);
    EXPECT_GT(misses, 1000);
    // Parallel to the axis: never on the wall.
    EXPECT_LT(cyl.intersectObject(Vec3(0.1f, 0, -5), Vec3(0, 0, 1), 0, 1e30f), 0);
}

// Normal away from the axis (flipped by ReverseOrientation), u = phi / phiMax,
// v = (z - zMin) / (zMax - zMin), in scene space under a non-uniform scale; area and the
// density of sampleArea follow the transform.
TEST(Cylinder, InteractionAreaAndSampling) {
    const Transform toScene = Transform::translate({1, 2, 3}) * Transform::scale({2, 2, 3});
    for (bool reverse : {false, true}) {
        Cylinder cyl(toScene, reverse, 0.5f, -1, 1, 180);
        const float phi = 0.6f, z = 0.25f;
        Vec3 target = toScene.point(wallPoint(0.5f, phi, z));
        Vec3 outward(std::cos(phi), std::sin(phi), 0);
        Ray ray{target + 2.0f * outward, -outward};
        Vec3 oObj = toScene.inverse().point(ray.o), dObj = toScene.inverse().vector(ray.d);
        float t = cyl.intersectObject(oObj, dObj, 0, 1e30f);
        ASSERT_NEAR(t, 2.0f, 1e-5f);
        SurfaceInteraction si;
        cyl.interaction(ray, t, 0, 0, 0, si);
        EXPECT_LT(length(si.p - target), 1e-5f);
        EXPECT_LT(length(si.ng - (reverse ? -outward : outward)), 1e-5f);
        EXPECT_NEAR(si.uv.x, phi / kPi, 1e-5f);
        EXPECT_NEAR(si.uv.y, (z + 1) / 2, 1e-5f);
        // Half a wall of radius 0.5 * 2 and height 2 * 3: pi * 1 * 6.
        EXPECT_NEAR(cyl.area(0), kPi * 6, 1e-4f);
        // Samples lie on the part of the wall, with its normal, and density 1 / area.
        std::mt19937 rng(5);
        std::uniform_real_distribution<float> U(0, 1);
        double sumZ = 0;
        for (int i = 0; i < 1000; ++i) {
            ShapeSample s = cyl.sampleArea(0, Vec2(U(rng), U(rng)));
            Vec3 q = toScene.inverse().point(s.p);
            EXPECT_NEAR(q.x * q.x + q.y * q.y, 0.25f, 1e-5f);
            EXPECT_GE(q.y, -1e-6f);  // phi in [0, pi]
            Vec3 nExpected = normalize(Vec3(q.x, q.y, 0));
            EXPECT_LT(length(s.n - (reverse ? -nExpected : nExpected)), 1e-4f);
            EXPECT_NEAR(s.pdf, 1 / (kPi * 6), 1e-6f);
            sumZ += q.z;
        }
        EXPECT_NEAR(sumZ / 1000, 0, 4 * std::sqrt(1.0 / 3 / 1000));  // z uniform on [-1, 1]
    }
}
