// Texture mappings (materials/texture_mapping.h) from Texture parameters and the CTM at the
// directive: each mapping's (s, t) at chosen points against values worked out by hand, the
// 3-D mapping, and the errors and warnings for bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/texture_mapping.h"
#include "param_builder.h"

using namespace ps;
using namespace ps::test;

namespace {

TextureEvalContext atPoint(Vec3 p, Vec2 uv = Vec2(0, 0)) {
    TextureEvalContext c;
    c.p = p;
    c.uv = uv;
    return c;
}

void expectST(const TextureMapping2D& m, Vec3 p, float s, float t, const char* what) {
    Vec2 st = m.map(atPoint(p));
    EXPECT_NEAR(st.x, s, 1e-6f) << what << ": s";
    EXPECT_NEAR(st.y, t, 1e-6f) << what << ": t";
}

const SourceLoc kLoc{"test.pbrt", 1, 1};

// Translates by (1, 2, 3) after scaling x by 2: textureFromWorld(p) = ((x - 1) / 2, y - 2, z - 3).
Transform ctm() { return Transform::translate(Vec3(1, 2, 3)) * Transform::scale(Vec3(2, 1, 1)); }

}  // namespace

// s = theta / pi from +z, t = phi / 2pi in [0, 1), of the direction of q = textureFromWorld(p).
TEST(TextureMapping, Spherical) {
    TextureMapping2D m = textureMapping2D(Params().s("mapping", "spherical"), ctm(), kLoc);
    EXPECT_EQ(m.kind(), TextureMapping2D::Kind::Spherical);
    expectST(m, Vec3(1, 2, 5), 0, 0, "q = (0, 0, 2): the +z pole");
    expectST(m, Vec3(1, 7, 3), 0.5f, 0.25f, "q = (0, 5, 0): equator, phi = pi/2");
    expectST(m, Vec3(-1, 2, 2), 0.75f, 0.5f, "q = (-1, 0, -1): theta = 3pi/4, phi = pi");
    expectST(m, Vec3(3, 1, 3 + std::sqrt(2.0f)), 0.25f, 0.875f, "q = (1, -1, sqrt 2): theta = pi/4, phi = 7pi/4");
    expectST(m, Vec3(1, 2, 3), 0, 0, "the centre (no direction) maps to (0, 0), not NaN");
}

// s = (pi + atan2(q.y, q.x)) / 2pi, t = q.z.
TEST(TextureMapping, Cylindrical) {
    TextureMapping2D m = textureMapping2D(Params().s("mapping", "cylindrical"), ctm(), kLoc);
    expectST(m, Vec3(3, 2, 8), 0.5f, 5, "q = (1, 0, 5): phi = 0");
    expectST(m, Vec3(1, 3, -1), 0.75f, -4, "q = (0, 1, -4): phi = pi/2");
    expectST(m, Vec3(-1, 1, 3.5f), 0.125f, 0.5f, "q = (-1, -1, 0.5): phi = -3pi/4");
}

// s = udelta + dot(q, v1), t = vdelta + dot(q, v2); v1, v2 are not normalised.
TEST(TextureMapping, Planar) {
    TextureMapping2D m = textureMapping2D(
        Params().s("mapping", "planar").vec("v1", 1, 0, 0).vec("v2", 0, 0, 2).f("udelta", 0.5).f("vdelta", -1), ctm(), kLoc);
    expectST(m, Vec3(5, 3, 7), 0.5f + 2, -1 + 8, "q = (2, 1, 4)");
    expectST(m, Vec3(0, 0, 0), 0.5f - 0.5f, -1 - 6, "q = (-0.5, -2, -3)");
    // Defaults: v1 = x, v2 = y, no offsets, identity CTM: (s, t) = (x, y).
    TextureMapping2D d = textureMapping2D(Params().s("mapping", "planar"), Transform(), kLoc);
    expectST(d, Vec3(0.3f, 0.7f, 9), 0.3f, 0.7f, "defaults");
}

// uv ignores the point and the CTM; an unknown mapping warns and is uv.
TEST(TextureMapping, UVAndUnknown) {
    TextureMapping2D m = textureMapping2D(Params().f("uscale", 2).f("vdelta", 0.25), ctm(), kLoc);
    Vec2 st = m.map(atPoint(Vec3(5, 5, 5), Vec2(0.5f, 0.5f)));
    EXPECT_FLOAT_EQ(st.x, 1.0f);
    EXPECT_FLOAT_EQ(st.y, 0.75f);
    setWarningsQuiet(true);
    int before = warningCount();
    TextureMapping2D u = textureMapping2D(Params().s("mapping", "bogus"), ctm(), kLoc);
    EXPECT_EQ(warningCount(), before + 1);
    EXPECT_EQ(u.kind(), TextureMapping2D::Kind::UV);
}

// 3-D textures see q = textureFromWorld(p).
TEST(TextureMapping, Solid) {
    TextureMapping3D m = textureMapping3D(ctm(), kLoc);
    Vec3 q = m.map(atPoint(Vec3(5, 3, 7)));
    EXPECT_NEAR(q.x, 2, 1e-6f);
    EXPECT_NEAR(q.y, 1, 1e-6f);
    EXPECT_NEAR(q.z, 4, 1e-6f);
}

// Mappings through the texture's space need its inverse: a singular CTM is a located error
// there, and no problem for uv.
TEST(TextureMapping, SingularTransformIsAnErrorWhereItMatters) {
    Transform flat = Transform::fromMatrixOrSingular([] {
        Matrix4 m;
        m.m[2][2] = 0;
        return m;
    }());
    for (const char* kind : {"spherical", "cylindrical", "planar"})
        EXPECT_THROW(textureMapping2D(Params().s("mapping", kind), flat, kLoc), InputError) << kind;
    EXPECT_THROW(textureMapping3D(flat, kLoc), InputError);
    EXPECT_NO_THROW(textureMapping2D(Params(), flat, kLoc));
}
