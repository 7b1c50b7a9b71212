// Bump and normal maps on a hand-made shading frame: the mapped normal against its closed
// form (pbrt-v4's semantics, PBRT-CONVENTIONS "Normal and bump maps"), and the "normalmap" /
// "displacement" material parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include "materials/create.h"
#include "materials/shading_detail.h"
#include "param_builder.h"

using namespace ps;
using namespace ps::test;

namespace {

// d(u, v) = a + k u: a linear ramp, so the finite difference is exact at any step.
class RampTexture final : public FloatTexture {
public:
    RampTexture(float a, float k) : a_(a), k_(k) {}
    float evaluate(const TextureEvalContext& ctx) const override { return a_ + k_ * ctx.uv.x; }

private:
    float a_, k_;
};

// A flat patch: n = +z, dp/du = (Lu, 0, 0), dp/dv = (0, Lv, 0), dn/du = dn/dv = 0.
SurfaceInteraction flatPatch(float Lu, float Lv) {
    SurfaceInteraction si;
    si.p = Vec3(0.2f, 0.3f, 0);
    si.ng = si.ns = Vec3(0, 0, 1);
    si.dpdu = Vec3(Lu, 0, 0);
    si.dpdv = Vec3(0, Lv, 0);
    si.uv = Vec2(0.4f, 0.6f);
    return si;
}

std::shared_ptr<const Image> onePixel(Spectrum c) {
    auto img = std::make_shared<Image>(1, 1);
    img->set(0, 0, c);
    return img;
}

void expectVec(Vec3 a, Vec3 b, float tol, const char* what) {
    std::printf("  %s: (%.7f %.7f %.7f), expected (%.7f %.7f %.7f)\n", what, a.x, a.y, a.z, b.x, b.y, b.z);
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

// Raising the surface by k per unit u over a tangent of length Lu tilts the normal by
// atan(k / Lu) away from the ascent: n = (-k, 0, Lu) / sqrt(k^2 + Lu^2).
TEST(ShadingDetail, BumpOfALinearRampTiltsTheNormalByTheKnownAngle) {
    const float Lu = 2, Lv = 3, k = 1.5f;
    SurfaceInteraction si = flatPatch(Lu, Lv);
    ShadingDetail::bumpMap(std::make_shared<RampTexture>(0.25f, k))->apply(si);
    float tilt = std::atan2(k, Lu);
    std::printf("  tilt %.6f rad (atan(k/Lu) = %.6f)\n", std::acos(si.ns.z), tilt);
    expectVec(si.ns, Vec3(-std::sin(tilt), 0, std::cos(tilt)), 2e-4f, "bumped normal");
    // The frame's tangent is the displaced dp/du: orthogonal to the new normal.
    EXPECT_NEAR(dot(si.ns, si.dpdu), 0, 1e-5f);
    EXPECT_FALSE(si.tangentIsFrameAxis);
    // A constant displacement on a flat patch (dn/du = 0) changes nothing.
    SurfaceInteraction flat = flatPatch(Lu, Lv);
    ShadingDetail::bumpMap(std::make_shared<RampTexture>(0.7f, 0))->apply(flat);
    expectVec(flat.ns, Vec3(0, 0, 1), 0, "constant displacement");
}

// pbrt-v4 displaces along the shading normal and then puts the result on the geometric
// normal's side: on a patch whose normal is the opposite of dp/du x dp/dv, the same ramp
// tilts towards -x as well (not the mirror image).
TEST(ShadingDetail, BumpedNormalFollowsTheGeometricNormalsSide) {
    const float Lu = 2, k = 1.5f;
    SurfaceInteraction si = flatPatch(Lu, 1);
    si.ng = si.ns = Vec3(0, 0, -1);
    ShadingDetail::bumpMap(std::make_shared<RampTexture>(0, k))->apply(si);
    float tilt = std::atan2(k, Lu);
    expectVec(si.ns, Vec3(-std::sin(tilt), 0, -std::cos(tilt)), 2e-4f, "reversed patch");
}

// The displacement times dn/du enters dp/du: on a patch whose normal turns with u
// (dn/du = (c, 0, 0)), a constant displacement d stretches dp/du to Lu + d c and leaves
// the normal, while a ramp's tilt becomes atan(k / (Lu + d c)).
TEST(ShadingDetail, BumpIncludesTheNormalsDerivative) {
    const float Lu = 2, k = 1.5f, c = 0.5f, a = 0.4f;
    SurfaceInteraction si = flatPatch(Lu, 1);
    si.dndu = Vec3(c, 0, 0);
    ShadingDetail::bumpMap(std::make_shared<RampTexture>(a, k))->apply(si);
    float d = a + k * si.uv.x;
    float tilt = std::atan2(k, Lu + d * c);
    expectVec(si.ns, Vec3(-std::sin(tilt), 0, std::cos(tilt)), 2e-4f, "with dn/du");
}

// The tangent frame is x = dp/du (unit), z = shading n, y = z x x: with dp/du along +y the
// map's (sin b, 0, cos b) lands at (0, sin b, cos b).
TEST(ShadingDetail, NormalMapIsReadInTheTangentFrame) {
    const float b = 0.5f;
    Vec3 local(std::sin(b), 0, std::cos(b));
    SurfaceInteraction si = flatPatch(1, 1);
    si.dpdu = Vec3(0, 4, 0);
    si.dpdv = Vec3(-2, 0, 0);
    auto map = ShadingDetail::normalMap(onePixel(Spectrum((local.x + 1) / 2, (local.y + 1) / 2, (local.z + 1) / 2)));
    map->apply(si);
    expectVec(si.ns, Vec3(0, std::sin(b), std::cos(b)), 1e-6f, "mapped normal");
    // dp/du keeps its length, made orthogonal to the new normal.
    EXPECT_NEAR(length(si.dpdu), 4, 1e-5f);
    EXPECT_NEAR(dot(si.dpdu, si.ns), 0, 1e-5f);
    // A map normal below the surface is flipped to the geometric normal's side.
    SurfaceInteraction below = flatPatch(1, 1);
    ShadingDetail::normalMap(onePixel(Spectrum(0.5f, 0.5f, 0.2f)))->apply(below);
    expectVec(below.ns, Vec3(0, 0, 1), 1e-6f, "map normal below the surface");
}

TEST(ShadingDetail, FlatNormalMapKeepsTheFrame) {
    SurfaceInteraction si = flatPatch(2, 3);
    si.dpdu = Vec3(2, 0.5f, 0);
    SurfaceInteraction before = si;
    ShadingDetail::normalMap(onePixel(Spectrum(0.5f, 0.5f, 1)))->apply(si);
    expectVec(si.ns, before.ns, 1e-7f, "normal");
    expectVec(normalize(si.dpdu), normalize(before.dpdu), 1e-7f, "tangent");
}

// A zero map normal (grey 0.5) or a missing dp/dv leave the frame as it was: no NaN.
TEST(ShadingDetail, DegenerateMapsLeaveTheFrame) {
    SurfaceInteraction si = flatPatch(1, 1);
    ShadingDetail::normalMap(onePixel(Spectrum(0.5f)))->apply(si);
    expectVec(si.ns, Vec3(0, 0, 1), 0, "zero map normal");
    SurfaceInteraction noDpdv = flatPatch(1, 0);
    ShadingDetail::bumpMap(std::make_shared<RampTexture>(0, 0))->apply(noDpdv);
    expectVec(noDpdv.ns, Vec3(0, 0, 1), 0, "no dp/dv");
}

class ShadingDetailParams : public ::testing::Test {
protected:
    void SetUp() override {
        setWarningsQuiet(true);
        dir_ = std::filesystem::temp_directory_path() / ("ps_shading_detail_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::shared_ptr<Material> make(const std::string& type, const Params& p) {
        return createMaterial(type, p, reg_, named_, dir_.string());
    }
    std::filesystem::path dir_;
    TextureRegistry reg_;
    std::map<std::string, std::shared_ptr<Material>> named_;
};

// PNG normal maps are read linearly: (128, 128, 255) is 2 * 128/255 - 1 = 1/255 off flat,
// where an sRGB decode would give 2 * 0.216 - 1 = -0.57 (a 39 degree tilt).
TEST_F(ShadingDetailParams, PngNormalMapIsReadLinearly) {
    Image img(1, 1);
    // writeImage sRGB-encodes PNG: this linear value is stored as the byte 128.
    img.set(0, 0, Spectrum(srgbToLinear(128 / 255.0f), srgbToLinear(128 / 255.0f), 1));
    writeImage((dir_ / "flat.png").string(), img);
    auto m = make("diffuse", Params().s("normalmap", "flat.png"));
    ASSERT_TRUE(m->shadingDetail());
    EXPECT_TRUE(m->needsShadingDerivatives());
    SurfaceInteraction si = flatPatch(1, 1);
    m->shadingDetail()->apply(si);
    float e = 2 * 128 / 255.0f - 1;
    expectVec(si.ns, normalize(Vec3(e, e, 1)), 1e-5f, "PNG (128, 128, 255)");
}

TEST_F(ShadingDetailParams, MissingNormalMapIsALocatedError) {
    Params p;
    p.s("normalmap", "nowhere.png");
    try {
        make("conductor", p);
        FAIL() << "no error";
    } catch (const InputError& e) {
        std::string msg = e.what();
        std::printf("  %s\n", msg.c_str());
        EXPECT_NE(msg.find("test.pbrt:"), std::string::npos) << msg;
        EXPECT_NE(msg.find("nowhere.png"), std::string::npos) << msg;
    }
}

TEST_F(ShadingDetailParams, DisplacementOnEveryScatteringMaterialAndMixMembers) {
    reg_.floats["bump"] = std::make_shared<RampTexture>(0, 1);
    for (const char* type : {"diffuse", "conductor", "dielectric", "thindielectric", "diffusetransmission",
                             "coateddiffuse", "coatedconductor"}) {
        auto m = make(type, Params().tex("displacement", "bump"));
        EXPECT_TRUE(m->shadingDetail()) << type;
        EXPECT_TRUE(m->needsShadingDerivatives()) << type;
    }
    EXPECT_TRUE(make("diffuse", Params().f("displacement", 0.1))->shadingDetail()) << "a constant displacement";
    EXPECT_THROW(make("diffuse", Params().tex("displacement", "undefined")), InputError);
    // mix has no map of its own, but hits on it need the derivatives for its members'.
    named_["bumpy"] = make("diffuse", Params().tex("displacement", "bump"));
    named_["plain"] = make("diffuse", Params());
    EXPECT_FALSE(named_["plain"]->needsShadingDerivatives());
    auto mix = make("mix", Params().s("materials", std::vector<std::string>{"plain", "bumpy"}));
    EXPECT_FALSE(mix->shadingDetail());
    EXPECT_TRUE(mix->needsShadingDerivatives());
    // A map on the mix itself is ignored with a warning (its members' maps apply).
    auto mapped = make("mix", Params().s("materials", std::vector<std::string>{"plain", "plain"}).tex("displacement", "bump"));
    EXPECT_FALSE(mapped->shadingDetail());
    EXPECT_FALSE(mapped->needsShadingDerivatives());
}

}  // namespace
