// Shape "curve" through Embree's curve primitives, against closed forms: a straight "flat" or
// "cylinder" curve is a strip of the width facing each ray (the cylinder's shaded as a tube),
// a straight "ribbon" a strip in the plane its normals give; widths vary linearly along the
// curve; degree 2 and B-spline curves equal the cubic Bezier curves they convert to exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "geometry/curve.h"
#include "render/scene.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "util/error.h"

using namespace ps;

namespace {

std::unique_ptr<Scene> sceneOf(const std::string& shapes) {
    setWarningsQuiet(true);
    return buildScene(parseSceneString(R"(
        LookAt 0 0 -5  0 0 0  0 1 0
        Camera "perspective"
        WorldBegin
    )" + shapes, ".", "<test>"));
}

// A straight curve from x = -2 to x = 2 on the x axis (control points evenly spaced, so u
// is linear in x).
std::string straightCurve(const std::string& type, const std::string& extra) {
    return "Shape \"curve\" \"string type\" \"" + type +
           "\" \"point3 P\" [ -2 0 0  -0.6666667 0 0  0.6666667 0 0  2 0 0 ] " + extra + "\n";
}

std::optional<SurfaceInteraction> trace(const Scene& scene, Vec3 o, Vec3 d) {
    SurfaceInteraction si;
    if (!scene.intersect(Ray{o, d, 1e30f}, si)) return std::nullopt;
    return si;
}

}  // namespace

// A flat curve is a strip of the curve's width facing each ray: whatever the direction, a
// ray hits iff it passes within w/2 of the centre line, at the depth of the centre line's
// closest point, with a normal perpendicular to the curve pointing away from the ray origin
// (pbrt-v4's orientation) and v = 1/2 + (signed distance) / w. A cylinder curve is the same
// strip (pbrt-v4's), shaded as a tube: its shading normal is the strip's turned about the
// curve by theta = (v - 1/2) pi, towards the side of the hit (as a tube's inner normal there);
// ReverseOrientation flips both normals.
TEST(Curve, FlatAndCylinderCurvesHaveTheProjectedWidth) {
  for (const char* type : {"flat", "cylinder"}) {
    SCOPED_TRACE(type);
    const bool cylinder = std::string(type) == "cylinder";
    const float w = 0.3f;
    auto scene = sceneOf(straightCurve(type, "\"float width\" [ 0.3 ]"));
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> U(0, 1);
    int hits = 0, misses = 0;
    double worstT = 0, worstV = 0;
    for (int i = 0; i < 4000; ++i) {
        Vec3 d = normalize(Vec3(U(rng) - 0.5f, 2 * U(rng) - 1, 1.2f));
        // Aimed at a point of the plane through the axis perpendicular to the ray.
        Vec3 across = normalize(cross(d, Vec3(1, 0, 0)));
        float x = 1.6f * (2 * U(rng) - 1), s = 1.2f * w * (2 * U(rng) - 1);
        Vec3 o = Vec3(x, 0, 0) + across * s - d * 5.0f;
        auto si = trace(*scene, o, d);
        if (std::fabs(s) > 0.51f * w) {
            EXPECT_FALSE(si) << "ray " << i << " at " << s;
            ++misses;
            continue;
        }
        if (std::fabs(s) > 0.49f * w) continue;
        ASSERT_TRUE(si) << "ray " << i << " at " << s;
        ++hits;
        // The centre line's closest point to the ray lies at depth 5 along it.
        worstT = std::max(worstT, double(std::fabs(si->t - 5)));
        EXPECT_NEAR(si->t, 5, 1e-3f) << "ray " << i;
        Vec3 nExact = normalize(d - Vec3(d.x, 0, 0));
        EXPECT_LT(length(si->ng - nExact), 1e-4f) << "ray " << i;
        float vExact = 0.5f + s / w;
        worstV = std::max(worstV, double(std::fabs(si->uv.y - vExact)));
        EXPECT_NEAR(si->uv.y, vExact, 2e-3f) << "ray " << i;
        const float theta = cylinder ? (vExact - 0.5f) * kPi : 0.0f;
        const Vec3 nsExact = nExact * std::cos(theta) - across * std::sin(theta);
        EXPECT_LT(length(si->ns - nsExact), 1e-2f) << "ray " << i << " at v " << vExact;
    }
    std::printf("  %s: %d hits, %d misses; largest |t - t_exact| %.2g, |v - v_exact| %.2g\n", type, hits, misses, worstT,
                worstV);
    EXPECT_GT(hits, 1000);
    EXPECT_GT(misses, 500);
    // ReverseOrientation flips both normals: a ray along +z a quarter width off the axis
    // towards -y, where v = 1/4 (across, d x axis, is +y).
    auto flipped = sceneOf("ReverseOrientation\n" + straightCurve(type, "\"float width\" [ 0.3 ]"));
    auto si = trace(*flipped, Vec3(0.3f, -0.075f, -5), Vec3(0, 0, 1));
    ASSERT_TRUE(si);
    EXPECT_NEAR(si->t, 5, 1e-3f);
    EXPECT_LT(length(si->ng - Vec3(0, 0, -1)), 1e-4f);
    const float theta = cylinder ? -0.25f * kPi : 0.0f;
    EXPECT_LT(length(si->ns - Vec3(0, std::sin(theta), -std::cos(theta))), 1e-2f) << si->ns.x << " " << si->ns.y << " "
                                                                                    << si->ns.z;
  }
}

// width0 0.2 to width1 0.6 over two segments: pbrt-v4 gives segment k the widths at k/2 and
// (k+1)/2 and interpolates linearly within it, so at x = -0.5 (segment 0, u = 1/2) the width is
// 0.3 and at x = 0.5 (segment 1, u = 1/2) it is 0.5. Rays along +z at 0.98 and 1.02 times the
// half width hit and miss, for flat and cylinder curves.
TEST(Curve, WidthIsInterpolatedLinearly) {
    for (const char* type : {"flat", "cylinder"}) {
        auto scene = sceneOf(std::string("Shape \"curve\" \"string type\" \"") + type +
                             "\" \"float width0\" [ 0.2 ] \"float width1\" [ 0.6 ]"
                             " \"point3 P\" [ -1 0 0  -0.6666667 0 0  -0.3333333 0 0  0 0 0"
                             "  0.3333333 0 0  0.6666667 0 0  1 0 0 ]\n");
        for (auto [x, w] : {std::pair{-0.5f, 0.3f}, std::pair{0.5f, 0.5f}}) {
            for (float sign : {-1.0f, 1.0f}) {
                auto in = trace(*scene, Vec3(x, sign * 0.49f * w, -5), Vec3(0, 0, 1));
                auto out = trace(*scene, Vec3(x, sign * 0.51f * w, -5), Vec3(0, 0, 1));
                std::printf("  %s at x = %+.1f, y = %+.3f: %s; y = %+.3f: %s\n", type, x, sign * 0.49f * w,
                            in ? "hit" : "miss", sign * 0.51f * w, out ? "hit" : "miss");
                EXPECT_TRUE(in) << type << " x " << x;
                EXPECT_FALSE(out) << type << " x " << x;
                if (in) {
                    EXPECT_NEAR(in->uv.x, 0.5f, 2e-3f);
                }
            }
        }
    }
}

// A ribbon whose normals are both +z is the strip |y| <= w/2 of the plane z = 0: oblique rays
// hit it where they cross the plane iff |y| <= w/2, and its normal is +z (-z reversed).
// Normals +z and +y at the ends twist it: at u = 1/2 pbrt-v4's interpolated normal is
// (0, 1, 1)/sqrt 2.
TEST(Curve, RibbonFollowsItsNormals) {
    const float w = 0.4f;
    for (bool reverse : {false, true}) {
        auto scene = sceneOf(std::string(reverse ? "ReverseOrientation\n" : "") +
                             straightCurve("ribbon", "\"float width\" [ 0.4 ] \"normal N\" [ 0 0 1  0 0 1 ]"));
        std::mt19937 rng(13);
        std::uniform_real_distribution<float> U(0, 1);
        int hits = 0, misses = 0;
        for (int i = 0; i < 2000; ++i) {
            Vec3 d = normalize(Vec3(U(rng) - 0.5f, 2 * U(rng) - 1, 0.6f));  // up to ~70 degrees from the normal
            Vec3 aim(1.6f * (2 * U(rng) - 1), 1.2f * w * (2 * U(rng) - 1), 0);
            Vec3 o = aim - d * 4.0f;
            auto si = trace(*scene, o, d);
            if (std::fabs(aim.y) > 0.51f * w) {
                EXPECT_FALSE(si) << "ray " << i;
                ++misses;
                continue;
            }
            if (std::fabs(aim.y) > 0.49f * w) continue;
            ASSERT_TRUE(si) << "ray " << i;
            ++hits;
            EXPECT_NEAR(si->t, 4, 2e-3f) << "ray " << i;
            EXPECT_LT(length(si->ng - Vec3(0, 0, reverse ? -1.0f : 1.0f)), 1e-4f) << "ray " << i;
        }
        std::printf("  %s: %d hits, %d misses\n", reverse ? "reversed" : "plain", hits, misses);
        EXPECT_GT(hits, 500);
        EXPECT_GT(misses, 500);
    }
    // Twisted by 90 degrees: at u the normal is (0, sin, cos)(90 u degrees), the strip's centre
    // (4u - 2, 0, 0).
    auto twisted = sceneOf(straightCurve("ribbon", "\"float width\" [ 0.4 ] \"normal N\" [ 0 0 1  0 1 0 ]"));
    for (float u : {0.25f, 0.5f}) {
        const float a = u * kPi / 2;
        const Vec3 n(0, std::sin(a), std::cos(a)), centre(4 * u - 2, 0, 0);
        auto si = trace(*twisted, centre + n * 3.0f, -n);
        ASSERT_TRUE(si);
        std::printf("  twisted ribbon at u = %.4f: t = %.5f, n = (%.5f %.5f %.5f), expected (0 %.5f %.5f)\n", si->uv.x,
                    si->t, si->ng.x, si->ng.y, si->ng.z, n.y, n.z);
        EXPECT_NEAR(si->uv.x, u, 1e-3f);
        EXPECT_NEAR(si->t, 3, 1e-3f);
        EXPECT_LT(length(si->ng - n), 1e-3f);
        // Seen edge-on, the strip is a line there: a ray 0.01 beside it misses (a strip
        // turned by more than 3 degrees would not).
        Vec3 edge = normalize(cross(n, Vec3(1, 0, 0)));
        EXPECT_FALSE(trace(*twisted, centre + edge * 3.0f + n * 0.01f, -edge)) << "u " << u;
    }
}

// Degree 2 (raised to 3) and B-spline curves (converted to Bezier) give the hits of the cubic
// Bezier curve written out by hand, for every type.
TEST(Curve, ConvertedBasesMatchTheirCubicBezier) {
    // Quadratic Bezier q0 q1 q2 = cubic (q0, (q0 + 2 q1)/3, (2 q1 + q2)/3, q2).
    const std::string quadratic = "\"integer degree\" [ 2 ] \"point3 P\" [ -1 0 0  0 0.9 0.3  1 0 0 ]";
    const std::string cubicOfQuadratic = "\"point3 P\" [ -1 0 0  -0.3333333 0.6 0.2  0.3333333 0.6 0.2  1 0 0 ]";
    // Uniform cubic B-spline p0..p3 = Bezier ((p0+4p1+p2)/6, (2p1+p2)/3, (p1+2p2)/3, (p1+4p2+p3)/6).
    const std::string bspline = "\"string basis\" \"bspline\" \"point3 P\" [ -2 0 0  -1 0.6 0  1 0.6 0.6  2 0 0 ]";
    const std::string cubicOfBspline = "\"point3 P\" [ -0.8333333 0.5 0.1  -0.3333333 0.6 0.2  0.3333333 0.6 0.4  0.8333333 0.5 0.4 ]";
    for (const char* type : {"flat", "cylinder", "ribbon"}) {
        std::string common = std::string("\"string type\" \"") + type + "\" \"float width\" [ 0.2 ]" +
                             (std::string(type) == "ribbon" ? " \"normal N\" [ 0 0 1  0 0.6 0.8 ]" : "");
        for (auto [converted, explicitCubic] : {std::pair{quadratic, cubicOfQuadratic}, std::pair{bspline, cubicOfBspline}}) {
            auto a = sceneOf("Shape \"curve\" " + common + " " + converted + "\n");
            auto b = sceneOf("Shape \"curve\" " + common + " " + explicitCubic + "\n");
            std::mt19937 rng(14);
            std::uniform_real_distribution<float> U(0, 1);
            int hits = 0, agree = 0;
            double worstT = 0;
            for (int i = 0; i < 2000; ++i) {
                Vec3 o(2.4f * U(rng) - 1.2f, 1.4f * U(rng) - 0.4f, -5);
                Vec3 d = normalize(Vec3(0.2f * (U(rng) - 0.5f), 0.2f * (U(rng) - 0.5f), 1));
                auto ha = trace(*a, o, d), hb = trace(*b, o, d);
                if (bool(ha) != bool(hb)) continue;  // only within float rounding of the silhouette
                ++agree;
                if (!ha) continue;
                ++hits;
                worstT = std::max(worstT, double(std::fabs(ha->t - hb->t)));
                EXPECT_NEAR(ha->t, hb->t, 1e-3f) << type << " ray " << i;
                EXPECT_NEAR(ha->uv.x, hb->uv.x, 1e-3f) << type << " ray " << i;
                EXPECT_LT(length(ha->ng - hb->ng), 1e-2f) << type << " ray " << i;
            }
            std::printf("  %s: %d of 2000 rays agree on hit or miss, %d hits, largest |t_a - t_b| %.2g\n", type, agree,
                        hits, worstT);
            EXPECT_GE(agree, 1990) << type;
            EXPECT_GT(hits, 150) << type;
        }
    }
}

// The conversions themselves are exact: the converted cubic passes through the points the
// original basis gives at u = 0, 1/2 and 1.
TEST(Curve, BasisConversionsAreExact) {
    const Vec3 q[3] = {{0, 0, 0}, {1, 2, 0}, {3, 0, 1}};
    auto bez = [](const std::array<Vec3, 4>& c, float u) {
        float s = 1 - u;
        return c[0] * (s * s * s) + c[1] * (3 * s * s * u) + c[2] * (3 * s * u * u) + c[3] * (u * u * u);
    };
    // Quadratic Bezier at 1/2: (q0 + 2 q1 + q2) / 4.
    EXPECT_LT(length(bez(elevateQuadraticBezier(q), 0.5f) - (q[0] + q[1] * 2.0f + q[2]) / 4.0f), 1e-6f);
    // Quadratic B-spline: ends at the midpoints, middle (q0 + 6 q1 + q2) / 8.
    auto qb = quadraticBSplineToBezier(q);
    EXPECT_LT(length(bez(qb, 0) - (q[0] + q[1]) * 0.5f), 1e-6f);
    EXPECT_LT(length(bez(qb, 0.5f) - (q[0] + q[1] * 6.0f + q[2]) / 8.0f), 1e-6f);
    EXPECT_LT(length(bez(qb, 1) - (q[1] + q[2]) * 0.5f), 1e-6f);
    // Cubic B-spline at 1/2: (p0 + 23 p1 + 23 p2 + p3) / 48.
    const Vec3 p[4] = {{0, 0, 0}, {1, 2, 0}, {3, 0, 1}, {4, 1, 2}};
    auto cb = cubicBSplineToBezier(p);
    EXPECT_LT(length(bez(cb, 0.5f) - (p[0] + p[1] * 23.0f + p[2] * 23.0f + p[3]) / 48.0f), 1e-5f);
}

// Rays leaving a point of a straight curve (spawned as integrators spawn them, to the side of
// the normal they leave by) never find that curve again: a flat curve or a ribbon with one
// normal is a planar strip, so any such hit would be the surface the ray starts on. Flat
// curves face every ray, so this is where they would shadow themselves. Rays leave to both
// sides: a tube (pbrt-v4's ray-facing strip shaded as a tube) lets rays that leave into it
// pass, as a hair BSDF's transmission through the fibre needs.
TEST(Curve, RaysLeavingACurveDoNotFindIt) {
    for (const char* type : {"flat", "ribbon", "cylinder"}) {
        auto scene = sceneOf(straightCurve(type, "\"float width\" [ 0.3 ] \"normal N\" [ 0 0 -1  0 0 -1 ]"));
        std::mt19937 rng(15);
        std::uniform_real_distribution<float> U(0, 1);
        int leaving = 0, found = 0, transmitted = 0;
        for (int i = 0; i < 8000; ++i) {
            Vec3 o(1.6f * (2 * U(rng) - 1), 0.1f * (2 * U(rng) - 1), -5);
            Vec3 d = normalize(Vec3(0.3f * (U(rng) - 0.5f), 0.02f * (U(rng) - 0.5f), 1));
            auto si = trace(*scene, o, d);
            if (!si) continue;
            Vec3 w = normalize(Vec3(2 * U(rng) - 1, 2 * U(rng) - 1, 2 * U(rng) - 1));
            ++leaving;
            if (dot(w, si->ng) * dot(-d, si->ng) < 0) ++transmitted;  // away from the side it came from
            if (trace(*scene, offsetRayOrigin(si->p, si->ng, w), w)) ++found;
        }
        std::printf("  %s: %d of %d rays leaving the curve (%d to the far side) find it again\n", type, found, leaving, transmitted);
        EXPECT_GT(transmitted, 2000) << type;
        EXPECT_EQ(found, 0) << type;
        EXPECT_GT(leaving, 5000) << type;
    }
}
