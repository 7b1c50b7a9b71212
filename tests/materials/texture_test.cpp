// Textures from parameter lists: constant, scale, mix, checkerboard (parity and uv mapping;
// the other mappings and procedural classes are in texture_mapping_test, procedural_texture_test)
// and image maps (v-flip, bilinear filtering, wrap modes, scale/invert, float = mean of RGB,
// PNG encoding, the image cache).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "image/image.h"
#include "materials/create.h"
#include "materials/image_texture.h"
#include "param_builder.h"

using namespace ps;
using namespace ps::test;

namespace {

TextureEvalContext at(float u, float v) {
    TextureEvalContext c;
    c.uv = Vec2(u, v);
    return c;
}

class Textures : public ::testing::Test {
protected:
    void SetUp() override { setWarningsQuiet(true); }
    std::shared_ptr<FloatTexture> ftex(const std::string& cls, const Params& p, const std::string& name = "t") {
        return createFloatTexture(textureEntity(name, cls, true, p), reg_, dir_);
    }
    std::shared_ptr<SpectrumTexture> stex(const std::string& cls, const Params& p, const std::string& name = "t") {
        return createSpectrumTexture(textureEntity(name, cls, false, p), reg_, dir_);
    }
    TextureRegistry reg_;
    std::string dir_;
};

TEST_F(Textures, Constant) {
    EXPECT_FLOAT_EQ(ftex("constant", Params())->evaluate(at(0, 0)), 1.0f);
    EXPECT_FLOAT_EQ(ftex("constant", Params().f("value", 0.25))->evaluate(at(3, 4)), 0.25f);
    Spectrum s = stex("constant", Params().rgb("value", 0.1, 0.2, 0.3))->evaluate(at(0, 0));
    EXPECT_FLOAT_EQ(s.b, 0.3f);
    // Spectrum textures keep values above 1 (they also feed unbounded quantities).
    EXPECT_FLOAT_EQ(stex("constant", Params().rgb("value", 2, 2, 2))->evaluate(at(0, 0)).r, 2.0f);
}

TEST_F(Textures, CheckerboardParity) {
    auto c = ftex("checkerboard", Params().f("tex1", 1.0).f("tex2", 0.0));
    EXPECT_EQ(c->evaluate(at(0.5f, 0.5f)), 1);    // floor 0 + 0: even -> tex1
    EXPECT_EQ(c->evaluate(at(1.5f, 0.5f)), 0);    // 1 + 0: odd -> tex2
    EXPECT_EQ(c->evaluate(at(1.5f, 1.5f)), 1);
    EXPECT_EQ(c->evaluate(at(-0.5f, 0.5f)), 0);   // floor(-0.5) = -1: odd
    EXPECT_EQ(c->evaluate(at(-0.5f, -0.5f)), 1);
    EXPECT_EQ(c->evaluate(at(1e9f, 0.5f)), 1);    // no overflow far away
    // Defaults: tex1 = 1, tex2 = 0.
    auto d = ftex("checkerboard", Params());
    EXPECT_EQ(d->evaluate(at(0.2f, 0.2f)), 1);
    EXPECT_EQ(d->evaluate(at(1.2f, 0.2f)), 0);
}

TEST_F(Textures, UVMapping) {
    // s = uscale u + udelta, t = vscale v + vdelta.
    auto c = ftex("checkerboard", Params().f("uscale", 4).f("vscale", 2).f("udelta", 0.5).f("vdelta", -0.25));
    auto expect = [&](float u, float v) {
        double s = 4 * u + 0.5, t = 2 * v - 0.25;
        return (int(std::floor(s)) + int(std::floor(t))) % 2 == 0 ? 1.0f : 0.0f;
    };
    for (float u : {0.01f, 0.1f, 0.2f, 0.3f, 0.45f, 0.6f, 0.9f})
        for (float v : {0.05f, 0.2f, 0.4f, 0.55f, 0.7f, 0.95f}) EXPECT_EQ(c->evaluate(at(u, v)), expect(u, v)) << u << "," << v;
}

TEST_F(Textures, UnsupportedModesWarnAndFallBack) {
    int before = warningCount();
    auto bogus = ftex("checkerboard", Params().s("mapping", "bogus"));
    EXPECT_EQ(warningCount(), before + 1);
    EXPECT_EQ(bogus->evaluate(at(1.5f, 0.5f)), 0);  // uv mapping
    auto unknown = ftex("ptex", Params());
    EXPECT_EQ(warningCount(), before + 2);
    EXPECT_EQ(unknown->evaluate(at(0, 0)), 1);
    ftex("constant", Params().f("value", 2).f("bogus", 1));  // unused parameter
    EXPECT_EQ(warningCount(), before + 3);
    // Parameters of another mapping are unused too.
    ftex("checkerboard", Params().s("mapping", "planar").f("uscale", 2));
    EXPECT_EQ(warningCount(), before + 4);
}

TEST_F(Textures, ScaleAndMix) {
    EXPECT_FLOAT_EQ(ftex("scale", Params().f("tex", 0.5).f("scale", 3))->evaluate(at(0, 0)), 1.5f);
    EXPECT_FLOAT_EQ(ftex("mix", Params().f("tex1", 0.2).f("tex2", 0.8).f("amount", 0.25))->evaluate(at(0, 0)), 0.35f);
    EXPECT_FLOAT_EQ(ftex("mix", Params())->evaluate(at(0, 0)), 0.5f);  // tex1 0, tex2 1, amount 0.5
    Spectrum s = stex("scale", Params().rgb("tex", 0.1, 0.2, 0.4).f("scale", 2))->evaluate(at(0, 0));
    EXPECT_FLOAT_EQ(s.b, 0.8f);
    // Textures referring to textures: a checkerboard amount mixes two colours.
    reg_.floats["checks"] = ftex("checkerboard", Params());
    reg_.spectra["red"] = stex("constant", Params().rgb("value", 1, 0, 0));
    auto mix = stex("mix", Params().tex("tex1", "red").rgb("tex2", 0, 0, 1).tex("amount", "checks"));
    EXPECT_FLOAT_EQ(mix->evaluate(at(0.5f, 0.5f)).b, 1.0f);  // amount 1: tex2
    EXPECT_FLOAT_EQ(mix->evaluate(at(1.5f, 0.5f)).r, 1.0f);  // amount 0: tex1
    EXPECT_THROW(stex("scale", Params().tex("tex", "missing")), InputError);
}

class ImageTextures : public Textures {
protected:
    void SetUp() override {
        Textures::SetUp();
        dir_ = (std::filesystem::temp_directory_path() / ("ps_texture_test_" + std::to_string(::getpid()))).string();
        std::filesystem::create_directories(dir_);
        // 2 x 2, row 0 at the top: red green / blue white.
        Image img(2, 2);
        img.set(0, 0, Spectrum(1, 0, 0));
        img.set(1, 0, Spectrum(0, 1, 0));
        img.set(0, 1, Spectrum(0, 0, 1));
        img.set(1, 1, Spectrum(1, 1, 1));
        writeImage(dir_ + "/quad.pfm", img);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
};

void expectRGB(Spectrum s, float r, float g, float b, const char* what) {
    EXPECT_NEAR(s.r, r, 1e-5f) << what;
    EXPECT_NEAR(s.g, g, 1e-5f) << what;
    EXPECT_NEAR(s.b, b, 1e-5f) << what;
}

TEST_F(ImageTextures, LookupFlipsVAndFiltersBilinearly) {
    auto t = stex("imagemap", Params().s("filename", "quad.pfm"));  // relative to the scene directory
    expectRGB(t->evaluate(at(0.25f, 0.25f)), 0, 0, 1, "uv (0,0) quarter is the bottom-left texel");
    expectRGB(t->evaluate(at(0.75f, 0.25f)), 1, 1, 1, "bottom-right");
    expectRGB(t->evaluate(at(0.25f, 0.75f)), 1, 0, 0, "top-left");
    expectRGB(t->evaluate(at(0.75f, 0.75f)), 0, 1, 0, "top-right");
    expectRGB(t->evaluate(at(0.5f, 0.5f)), 0.5f, 0.5f, 0.5f, "centre: mean of the four");
    expectRGB(t->evaluate(at(0.5f, 0.25f)), 0.5f, 0.5f, 1, "between the bottom texels");
    // Repeat (default): u = -0.25 wraps to the right column.
    expectRGB(t->evaluate(at(-0.25f, 0.25f)), 1, 1, 1, "repeat");
    expectRGB(t->evaluate(at(1.25f, 1.75f)), 1, 0, 0, "repeat");
}

TEST_F(ImageTextures, WrapScaleInvert) {
    auto clampT = stex("imagemap", Params().s("filename", dir_ + "/quad.pfm").s("wrap", "clamp"));
    expectRGB(clampT->evaluate(at(-0.25f, 0.25f)), 0, 0, 1, "clamp");
    auto black = stex("imagemap", Params().s("filename", "quad.pfm").s("wrap", "black"));
    expectRGB(black->evaluate(at(-0.25f, 0.25f)), 0, 0, 0, "black");
    expectRGB(black->evaluate(at(0.0f, 0.25f)), 0, 0, 0.5f, "black: half a texel outside");
    auto scaled = stex("imagemap", Params().s("filename", "quad.pfm").f("scale", 0.5));
    expectRGB(scaled->evaluate(at(0.75f, 0.25f)), 0.5f, 0.5f, 0.5f, "scale");
    auto inverted = stex("imagemap", Params().s("filename", "quad.pfm").b("invert", true));
    expectRGB(inverted->evaluate(at(0.25f, 0.75f)), 0, 1, 1, "invert");
    auto both = stex("imagemap", Params().s("filename", "quad.pfm").f("scale", 2).b("invert", true));
    expectRGB(both->evaluate(at(0.25f, 0.75f)), 0, 1, 1, "scale then invert, clamped at 0");
    // Float image textures average the channels.
    auto f = ftex("imagemap", Params().s("filename", "quad.pfm"));
    EXPECT_NEAR(f->evaluate(at(0.25f, 0.25f)), 1.0f / 3, 1e-6f);
    EXPECT_NEAR(f->evaluate(at(0.75f, 0.25f)), 1.0f, 1e-6f);
    EXPECT_THROW(stex("imagemap", Params().s("filename", "missing.pfm")), InputError);
    EXPECT_THROW(stex("imagemap", Params()), InputError);
}

// 8-bit PNGs decode as sRGB unless `encoding` says "linear".
TEST_F(ImageTextures, PngEncoding) {
    Image img(1, 1);
    img.set(0, 0, Spectrum(0.5f));
    writeImage(dir_ + "/grey.png", img);  // stored sRGB-encoded: 188/255
    float srgb = stex("imagemap", Params().s("filename", "grey.png"))->evaluate(at(0.5f, 0.5f)).g;
    float lin = stex("imagemap", Params().s("filename", "grey.png").s("encoding", "linear"))->evaluate(at(0.5f, 0.5f)).g;
    EXPECT_NEAR(srgb, 0.5f, 5e-3f);
    EXPECT_NEAR(lin, linearToSrgb(0.5f), 5e-3f);
}

TEST_F(ImageTextures, EachFileIsReadOnce) {
    auto a = loadTextureImage(dir_ + "/quad.pfm", ColorEncoding::SRGB);
    auto b = loadTextureImage(dir_ + "/./quad.pfm", ColorEncoding::Linear);  // not a PNG: encoding irrelevant
    EXPECT_EQ(a.get(), b.get());
}

TEST(ImageLookup, FloatLookupsReturnAlphaWhenNotOpaque) {
    auto img = std::make_shared<Image>(1, 1);
    img->set(0, 0, Spectrum(0.3f, 0.6f, 0.9f));
    EXPECT_FALSE(hasNonOpaqueAlpha(*img));
    img->alpha = {0.25f};
    EXPECT_TRUE(hasNonOpaqueAlpha(*img));
    ImageLookup l(img, TextureMapping2D{}, WrapMode::Repeat, 1, false, ImageChannels::Alpha);
    EXPECT_FLOAT_EQ(l.evaluate(at(0.3f, 0.3f)).r, 0.25f);
    ImageLookup m(img, TextureMapping2D{}, WrapMode::Repeat, 1, false, ImageChannels::Average);
    EXPECT_NEAR(m.evaluate(at(0.3f, 0.3f)).r, 0.6f, 1e-6f);
}

}  // namespace
