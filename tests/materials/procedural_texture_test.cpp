// The procedural texture classes from Texture parameters: directionmix, dots, bilerp, fbm,
// wrinkled, windy, marble and the 3-D checkerboard, each against its definition at chosen
// points (PBRT-CONVENTIONS §6), with their defaults and their errors.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/create.h"
#include "materials/noise.h"
#include "materials/procedural_textures.h"
#include "param_builder.h"

using namespace ps;
using namespace ps::test;

namespace {

TextureEvalContext at(Vec3 p, Vec3 n = Vec3(0, 0, 1), Vec2 uv = Vec2(0, 0)) {
    TextureEvalContext c;
    c.p = p;
    c.n = n;
    c.uv = uv;
    return c;
}

class Procedural : public ::testing::Test {
protected:
    void SetUp() override { setWarningsQuiet(true); }
    std::shared_ptr<FloatTexture> ftex(const std::string& cls, const Params& p, const Transform& ctm = Transform()) {
        TextureEntity e = textureEntity("t", cls, true, p);
        e.worldFromTexture = ctm;
        return createFloatTexture(e, reg_, "");
    }
    std::shared_ptr<SpectrumTexture> stex(const std::string& cls, const Params& p, const Transform& ctm = Transform()) {
        TextureEntity e = textureEntity("t", cls, false, p);
        e.worldFromTexture = ctm;
        return createSpectrumTexture(e, reg_, "");
    }
    TextureRegistry reg_;
};

}  // namespace

// amount = |dot(n, dir)|, dir through the CTM: Rotate 90 about z takes the default dir
// (0, 1, 0) to (-1, 0, 0). tex1 weighs amount, tex2 1 - amount.
TEST_F(Procedural, DirectionMix) {
    Transform rot = Transform::rotate(90, Vec3(0, 0, 1));
    auto t = ftex("directionmix", Params().f("tex1", 10).f("tex2", 20), rot);
    EXPECT_NEAR(t->evaluate(at(Vec3(0, 0, 0), Vec3(1, 0, 0))), 10, 1e-5);
    EXPECT_NEAR(t->evaluate(at(Vec3(0, 0, 0), Vec3(-1, 0, 0))), 10, 1e-5);
    EXPECT_NEAR(t->evaluate(at(Vec3(0, 0, 0), Vec3(0, 1, 0))), 20, 1e-5);
    EXPECT_NEAR(t->evaluate(at(Vec3(0, 0, 0), Vec3(0.6f, 0.8f, 0))), 0.6 * 10 + 0.4 * 20, 1e-5);
    // Defaults tex1 0, tex2 1, dir +y; dir is normalised.
    auto d = ftex("directionmix", Params());
    EXPECT_NEAR(d->evaluate(at(Vec3(0, 0, 0), Vec3(0, 0.8f, 0.6f))), 0.2, 1e-6);
    auto s = stex("directionmix", Params().rgb("tex1", 1, 0, 0).rgb("tex2", 0, 0, 1).vec("dir", 0, 0, 5));
    Spectrum v = s->evaluate(at(Vec3(0, 0, 0), Vec3(0, 0.6f, 0.8f)));
    EXPECT_NEAR(v.r, 0.8, 1e-6);
    EXPECT_NEAR(v.b, 0.2, 1e-6);
    EXPECT_THROW(ftex("directionmix", Params().vec("dir", 0, 0, 0)), InputError);
}

// Inside a dot pbrt-v4 shows the "outside" value and elsewhere the "inside" one (its
// constructor receives them swapped); defaults inside 1, outside 0 thus give 0 in the dots.
TEST_F(Procedural, DotsAsPbrtV4) {
    // A cell with a dot: the noise at its centre is positive; its centre is within 0.15 of the
    // cell's integer point, so that point is inside; (0.5, 0.5)-shifted corners are outside.
    int found = 0;
    auto t = ftex("dots", Params().f("inside", 3).f("outside", 7).s("mapping", "planar"));
    auto d = ftex("dots", Params());
    for (int i = 0; i < 8 && found < 3; ++i)
        for (int j = 0; j < 8 && found < 3; ++j) {
            if (!(perlinNoise(i + 0.5f, j + 0.5f) > 0)) continue;
            ++found;
            EXPECT_EQ(t->evaluate(at(Vec3(float(i), float(j), 0))), 7) << i << "," << j;
            EXPECT_EQ(t->evaluate(at(Vec3(i + 0.49f, j + 0.49f, 0))), 3) << i << "," << j;
            EXPECT_EQ(d->evaluate(at(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec2(float(i), float(j)))), 0) << "uv mapping, defaults";
        }
    EXPECT_EQ(found, 3);
}

// v00 at (0,0), v10 at (1,0), v01 at (0,1), v11 at (1,1); defaults 0, 0, 1, 1 (v01 = v11 = 1).
TEST_F(Procedural, Bilerp) {
    auto t = ftex("bilerp", Params().f("v00", 1).f("v10", 2).f("v01", 3).f("v11", 5));
    auto uvAt = [&](float u, float v) { return t->evaluate(at(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec2(u, v))); };
    EXPECT_FLOAT_EQ(uvAt(0, 0), 1);
    EXPECT_FLOAT_EQ(uvAt(1, 0), 2);
    EXPECT_FLOAT_EQ(uvAt(0, 1), 3);
    EXPECT_FLOAT_EQ(uvAt(1, 1), 5);
    EXPECT_FLOAT_EQ(uvAt(0.5f, 0.5f), 2.75f);
    auto d = stex("bilerp", Params());
    EXPECT_FLOAT_EQ(d->evaluate(at(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec2(0.3f, 0.25f))).g, 0.25f);
}

// fbm / wrinkled: the octave sums at the texture-space point (CTM: Scale 2, so q = p / 2);
// defaults octaves 8, roughness 0.5.
TEST_F(Procedural, FBmAndWrinkled) {
    Transform s2 = Transform::scale(Vec3(2, 2, 2));
    const Vec3 p(3.1f, -1.7f, 0.9f), q = p * 0.5f;
    EXPECT_NEAR(ftex("fbm", Params().i("octaves", 3).f("roughness", 0.7), s2)->evaluate(at(p)), fbm(q, 0.7f, 3), 1e-6);
    EXPECT_NEAR(ftex("fbm", Params().i("octaves", 1), s2)->evaluate(at(p)), perlinNoise(q), 1e-6);
    EXPECT_NEAR(ftex("fbm", Params())->evaluate(at(p)), fbm(p, 0.5f, 8), 1e-6);
    EXPECT_NEAR(ftex("wrinkled", Params().i("octaves", 2), s2)->evaluate(at(p)), turbulence(q, 0.5f, 2), 1e-6);
    EXPECT_NEAR(ftex("windy", Params())->evaluate(at(p)), std::fabs(fbm(p * 0.1f, 0.5f, 3)) * fbm(p, 0.5f, 6), 1e-6);
    EXPECT_THROW(ftex("fbm", Params().i("octaves", -1)), InputError);
    EXPECT_THROW(ftex("wrinkled", Params().i("octaves", 100)), InputError);
}

// marble: 1.5 x the cubic Bezier segment of the nine control colours picked by
// t = 0.5 + 0.5 sin(y + variation fbm) at q = scale * textureFromWorld(p), here by de
// Casteljau's construction.
TEST_F(Procedural, Marble) {
    const Spectrum c[9] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f}, {.5f, .5f, .5f},  {.6f, .59f, .58f},
                           {.58f, .58f, .6f}, {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
    auto t = stex("marble", Params().f("scale", 2).f("variation", 0.5).i("octaves", 4).f("roughness", 0.6));
    for (Vec3 p : {Vec3(0.1f, 0.2f, 0.3f), Vec3(-1.3f, 0.77f, 2.1f), Vec3(4, -2.2f, 0.5f), Vec3(0.4f, 1.35f, -0.8f)}) {
        Vec3 q = p * 2.0f;
        double x = 0.5 + 0.5 * std::sin(q.y + 0.5 * fbm(q, 0.6f, 4));
        int first = std::min(int(std::floor(x * 6)), 5);
        double u = x * 6 - first;
        Spectrum expect;
        for (int ch = 0; ch < 3; ++ch) {
            double a[4] = {c[first][ch], c[first + 1][ch], c[first + 2][ch], c[first + 3][ch]};
            for (int level = 3; level > 0; --level)
                for (int k = 0; k < level; ++k) a[k] = (1 - u) * a[k] + u * a[k + 1];
            expect[ch] = float(1.5 * a[0]);
        }
        Spectrum v = t->evaluate(at(p));
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(v[ch], expect[ch], 1e-5) << "segment " << first;
    }
}

// dimension 3: tex1 where floor(x) + floor(y) + floor(z) of q is even. CTM Scale 0.5: q = 2p.
TEST_F(Procedural, SolidCheckerboard) {
    auto t = ftex("checkerboard", Params().i("dimension", 3).f("tex1", 1).f("tex2", 0), Transform::scale(Vec3(0.5f, 0.5f, 0.5f)));
    EXPECT_EQ(t->evaluate(at(Vec3(0.25f, 0.25f, 0.25f))), 1);   // q cell (0, 0, 0)
    EXPECT_EQ(t->evaluate(at(Vec3(0.75f, 0.25f, 0.25f))), 0);   // (1, 0, 0)
    EXPECT_EQ(t->evaluate(at(Vec3(0.75f, 0.75f, 0.25f))), 1);   // (1, 1, 0)
    EXPECT_EQ(t->evaluate(at(Vec3(0.75f, 0.75f, 0.75f))), 0);   // (1, 1, 1)
    EXPECT_EQ(t->evaluate(at(Vec3(-0.25f, 0.25f, 0.25f))), 0);  // (-1, 0, 0)
    EXPECT_EQ(t->evaluate(at(Vec3(-0.25f, -0.25f, 0.25f))), 1); // (-1, -1, 0)
    EXPECT_THROW(ftex("checkerboard", Params().i("dimension", 4)), InputError);
}

// Classes pbrt-v4 has only for the other kind (or not at all) still warn and give constant 1.
TEST_F(Procedural, WrongKindWarns) {
    int before = warningCount();
    EXPECT_EQ(ftex("marble", Params())->evaluate(at(Vec3(0, 0, 0))), 1);
    EXPECT_EQ(stex("fbm", Params())->evaluate(at(Vec3(0, 0, 0))).g, 1);
    EXPECT_EQ(warningCount(), before + 2);
}
