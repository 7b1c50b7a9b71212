// The shading derivatives that bump and normal maps read (SurfaceInteraction dpdu, dpdv,
// dndu, dndv), as pbrt-v4's shapes define them, against each surface's closed form: hits
// carry them only when the material has a map.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/scene.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "util/error.h"

using namespace ps;

namespace {

// The first hit of a ray from `o` towards `target` in a scene made of `shapes`.
SurfaceInteraction hit(const std::string& shapes, Vec3 o, Vec3 target) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(R"(
        LookAt 0 0 5  0 0 0  0 1 0
        Camera "perspective"
        WorldBegin
        Material "diffuse" "float displacement" [ 0 ]
    )" + shapes, ".", "<test>"));
    SurfaceInteraction si;
    EXPECT_TRUE(scene->intersect(Ray{o, normalize(target - o), 1e30f}, si));
    return si;
}

void expectVec(Vec3 a, Vec3 b, const char* what, float tol = 2e-5f) {
    std::printf("  %s: (%.6f %.6f %.6f), expected (%.6f %.6f %.6f)\n", what, a.x, a.y, a.z, b.x, b.y, b.z);
    float scale = std::max(1.0f, length(b));
    EXPECT_NEAR(a.x, b.x, tol * scale) << what;
    EXPECT_NEAR(a.y, b.y, tol * scale) << what;
    EXPECT_NEAR(a.z, b.z, tol * scale) << what;
}

// Full sphere of radius r: u = phi / 2pi, v = 1 - theta / pi, so dp/du = 2pi (-y, x, 0),
// dp/dv = -pi dp/dtheta, and the outward normal p / r has dn/du = dp/du / r (likewise in v).
// ReverseOrientation flips n, not its derivatives (as pbrt-v4).
TEST(ShadingDerivatives, SphereMatchesItsParameterisation) {
    const float r = 2, theta = 1.1f, phi = 0.7f;
    Vec3 p = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)) * r;
    Vec3 dpdu = Vec3(-p.y, p.x, 0) * (2 * kPi);
    Vec3 dpdtheta = Vec3(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), -std::sin(theta)) * r;
    Vec3 dpdv = dpdtheta * -kPi;
    for (bool reverse : {false, true}) {
        SCOPED_TRACE(reverse ? "reversed" : "outward");
        SurfaceInteraction si = hit(std::string(reverse ? "ReverseOrientation\n" : "") + R"(Shape "sphere" "float radius" [ 2 ])",
                                    p * 3, p);
        expectVec(si.p, p, "p");
        expectVec(si.ns, p / r * (reverse ? -1.0f : 1.0f), "ns");
        expectVec(si.dpdu, dpdu, "dpdu");
        expectVec(si.dpdv, dpdv, "dpdv");
        expectVec(si.dndu, dpdu / r, "dndu");
        expectVec(si.dndv, dpdv / r, "dndv");
        EXPECT_FALSE(si.tangentIsFrameAxis);
    }
}

// The same sphere as an instance rotated 90 degrees about z: every vector rotates with it.
TEST(ShadingDerivatives, InstancesCarryThemToTheWorld) {
    const float r = 2, theta = 1.1f, phi = 0.7f;
    Vec3 pLocal = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)) * r;
    auto rot = [](Vec3 v) { return Vec3(-v.y, v.x, v.z); };
    Vec3 p = rot(pLocal);
    Vec3 dpdv = Vec3(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), -std::sin(theta)) * (-kPi * r);
    SurfaceInteraction si = hit(R"(
        ObjectBegin "ball"
          Shape "sphere" "float radius" [ 2 ]
        ObjectEnd
        Rotate 90 0 0 1
        ObjectInstance "ball")",
                                p * 3, p);
    expectVec(si.p, p, "p");
    expectVec(si.dpdu, rot(Vec3(-pLocal.y, pLocal.x, 0) * (2 * kPi)), "dpdu");
    expectVec(si.dpdv, rot(dpdv), "dpdv");
    expectVec(si.dndv, rot(dpdv) / r, "dndv");
}

// Cylinder of radius 1, z in [0, 2]: dp/dv = (0, 0, 2), dn/du = dp/du / r, dn/dv = 0.
// Disk of radius 1, inner radius 0.5: dp/dv = -(x, y, 0) / rho * (1 - 0.5), no dn.
TEST(ShadingDerivatives, CylinderAndDisk) {
    const float phi = 2.0f;
    Vec3 p(std::cos(phi), std::sin(phi), 0.5f);
    SurfaceInteraction c = hit(R"(Shape "cylinder" "float radius" [ 1 ] "float zmin" [ 0 ] "float zmax" [ 2 ])",
                               Vec3(p.x * 3, p.y * 3, p.z), p);
    expectVec(c.dpdu, Vec3(-p.y, p.x, 0) * (2 * kPi), "cylinder dpdu");
    expectVec(c.dpdv, Vec3(0, 0, 2), "cylinder dpdv");
    expectVec(c.dndu, Vec3(-p.y, p.x, 0) * (2 * kPi), "cylinder dndu");
    expectVec(c.dndv, Vec3(0, 0, 0), "cylinder dndv");
    Vec3 q(0.3f, 0.5f, 0);
    float rho = std::sqrt(0.34f);
    SurfaceInteraction d = hit(R"(Shape "disk" "float radius" [ 1 ] "float innerradius" [ 0.5 ])", Vec3(0.3f, 0.5f, 2), q);
    expectVec(d.dpdu, Vec3(-q.y, q.x, 0) * (2 * kPi), "disk dpdu");
    expectVec(d.dpdv, Vec3(q.x, q.y, 0) * (-0.5f / rho), "disk dpdv");
    expectVec(d.dndu, Vec3(0, 0, 0), "disk dndu");
}

// A triangle with uv (0,0), (2,0), (0,3): dp/du = (0.5, 0, 0), dp/dv = (0, 1/3, 0). Without N
// these are the shading derivatives; with N, dp/du is made orthogonal to the interpolated
// normal ns (ss = (ns x dpdu) x ns), dp/dv = ns x dp/du, and dn/du = (n1 - n0) / 2,
// dn/dv = (n2 - n0) / 3 from the (unit) vertex normals.
TEST(ShadingDerivatives, TriangleFromItsUvAndNormals) {
    const std::string P = R"("point3 P" [ 0 0 0  1 0 0  0 1 0 ] "point2 uv" [ 0 0  2 0  0 3 ] "integer indices" [ 0 1 2 ])";
    SurfaceInteraction flat = hit(R"(Shape "trianglemesh" )" + P, Vec3(0.2f, 0.3f, 2), Vec3(0.2f, 0.3f, 0));
    expectVec(flat.dpdu, Vec3(0.5f, 0, 0), "dpdu");
    expectVec(flat.dpdv, Vec3(0, 1 / 3.0f, 0), "dpdv");
    expectVec(flat.dndu, Vec3(0, 0, 0), "dndu");
    Vec3 n0(0, 0, 1), n1 = normalize(Vec3(1, 0, 1)), n2 = normalize(Vec3(0, 1, 1));
    SurfaceInteraction s = hit(R"(Shape "trianglemesh" "normal N" [ 0 0 1  1 0 1  0 1 1 ] )" + P, Vec3(0.2f, 0.3f, 2),
                               Vec3(0.2f, 0.3f, 0));
    Vec3 ns = normalize(n0 * 0.5f + n1 * 0.2f + n2 * 0.3f);
    expectVec(s.ns, ns, "ns");
    Vec3 ss = cross(cross(ns, Vec3(0.5f, 0, 0)), ns);
    expectVec(s.dpdu, ss, "dpdu");
    expectVec(s.dpdv, cross(ns, Vec3(0.5f, 0, 0)), "dpdv");
    expectVec(s.dndu, (n1 - n0) / 2, "dndu");
    expectVec(s.dndv, (n2 - n0) / 3, "dndv");
}

// Without a map the hit carries none of it (and keeps the precomputed unit tangent).
TEST(ShadingDerivatives, OnlyForMaterialsWithAMap) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(R"(
        Camera "perspective"
        WorldBegin
        Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  0 1 0 ] "point2 uv" [ 0 0  2 0  0 3 ] "integer indices" [ 0 1 2 ]
    )", ".", "<test>"));
    SurfaceInteraction si;
    ASSERT_TRUE(scene->intersect(Ray{Vec3(0.2f, 0.3f, 2), Vec3(0, 0, -1), 1e30f}, si));
    expectVec(si.dpdv, Vec3(0, 0, 0), "dpdv");
    EXPECT_TRUE(si.tangentIsFrameAxis);
}

}  // namespace
