// The ColorSpace directive: RGB values written under it are converted into the rendering
// space (linear sRGB) by their use, the film's space converts the output image, and
// AttributeEnd restores the space. Expected values come from published standards (BT.709 to
// BT.2020, BT.2020's luminance coefficients) and from the chromaticity code of spectra.cpp,
// not from the matrices under test.
#include <gtest/gtest.h>

#include <cstdio>

#include "render/render_helpers.h"
#include "render/spectral_answer.h"
#include "scene/color_space.h"
#include "scene/spectra.h"

using namespace ps;

namespace {

void expectNear(Spectrum a, Spectrum b, float tol, const char* what) {
    std::printf("%-44s (%.4f %.4f %.4f), expected (%.4f %.4f %.4f)\n", what, a.r, a.g, a.b, b.r, b.g, b.b);
    EXPECT_NEAR(a.r, b.r, tol) << what;
    EXPECT_NEAR(a.g, b.g, tol) << what;
    EXPECT_NEAR(a.b, b.b, tol) << what;
}

Spectrum times(const std::array<float, 9>& m, Spectrum v) {
    return {m[0] * v.r + m[1] * v.g + m[2] * v.b, m[3] * v.r + m[4] * v.g + m[5] * v.b, m[6] * v.r + m[7] * v.g + m[8] * v.b};
}

// sRGB luminance coefficients (BT.709).
double luminance(Spectrum s) { return 0.2126 * s.r + 0.7152 * s.g + 0.0722 * s.b; }

}  // namespace

TEST(ColorSpace, NamesAndTheSrgbIdentity) {
    EXPECT_EQ(namedColorSpace("sRGB"), &srgbColorSpace());
    ASSERT_NE(namedColorSpace("ACES2065-1"), nullptr);
    ASSERT_NE(namedColorSpace("rec2020"), nullptr);
    ASSERT_NE(namedColorSpace("dci-p3"), nullptr);
    EXPECT_EQ(namedColorSpace("adobergb"), nullptr);
    const Spectrum v(0.3f, 0.6f, 0.9f);
    for (SpectrumKind k : {SpectrumKind::Albedo, SpectrumKind::Unbounded, SpectrumKind::Illuminant}) {
        for (const RGBColorSpace* space : {&srgbColorSpace(), static_cast<const RGBColorSpace*>(nullptr)}) {
            const Spectrum c = toRenderingSpace(v, space, k);
            EXPECT_TRUE(c.r == v.r && c.g == v.g && c.b == v.b);
        }
    }
}

TEST(ColorSpace, ConversionsAgainstPublishedValues) {
    const RGBColorSpace& rec2020 = *namedColorSpace("rec2020");
    const RGBColorSpace& aces = *namedColorSpace("aces2065-1");
    // BT.2087: BT.709 red, green, blue in BT.2020 (the conversion matrix's columns).
    const auto out2020 = outputFromRenderingSpace(rec2020);
    expectNear(times(out2020, {1, 0, 0}), {0.6274f, 0.0691f, 0.0164f}, 2e-3f, "sRGB red as BT.2020");
    expectNear(times(out2020, {0, 1, 0}), {0.3293f, 0.9195f, 0.0880f}, 2e-3f, "sRGB green as BT.2020");
    expectNear(times(out2020, {1, 1, 1}), {1, 1, 1}, 1e-5f, "sRGB white as BT.2020 (both D65)");
    // BT.2020's luminance coefficients (0.2627, 0.6780, 0.0593) survive the trip to sRGB:
    // an emitted colour inside sRGB's gamut keeps its luminance.
    const Spectrum mix(0.5f, 0.4f, 0.3f);
    const double y2020 = 0.2627 * 0.5 + 0.6780 * 0.4 + 0.0593 * 0.3;
    const double y = luminance(toRenderingSpace(mix, &rec2020, SpectrumKind::Illuminant));
    std::printf("BT.2020 (0.5 0.4 0.3) emitted: luminance %.5f, expected %.5f\n", y, y2020);
    EXPECT_NEAR(y, y2020, 1e-3);
    // Out and back: the film's conversion inverts the emitted colour's.
    expectNear(times(out2020, toRenderingSpace(mix, &rec2020, SpectrumKind::Illuminant)), mix, 1e-4f,
               "BT.2020 emitted, rendered, written as BT.2020");
    // An ACES white light emits the ACES white, D60 (x 0.32168, y 0.33767) at luminance 1.
    expectNear(toRenderingSpace({1, 1, 1}, &aces, SpectrumKind::Illuminant), chromaticityToRGB(0.32168, 0.33767),
               2e-3f, "ACES white light in sRGB");
    // A reflectance of 1 is white in every space; grey stays grey.
    expectNear(toRenderingSpace({1, 1, 1}, &aces, SpectrumKind::Albedo), {1, 1, 1}, 1e-4f, "ACES white reflectance");
    expectNear(toRenderingSpace({0.5f, 0.5f, 0.5f}, &aces, SpectrumKind::Unbounded), {0.5f, 0.5f, 0.5f}, 1e-4f,
               "ACES grey (unbounded)");
    // BT.2020's green is outside sRGB: clipped to non-negative, a reflectance also to 1.
    const Spectrum g = toRenderingSpace({0, 1, 0}, &rec2020, SpectrumKind::Albedo);
    std::printf("BT.2020 green reflectance in sRGB: (%.4f %.4f %.4f)\n", g.r, g.g, g.b);
    EXPECT_EQ(g.r, 0.0f);
    EXPECT_EQ(g.b, 0.0f);
    EXPECT_LE(g.g, 1.0f);
    EXPECT_GT(g.g, 0.5f);
}

// End to end, path tracing a sky seen directly (exact at any sample count in RGB mode): a light
// written under ColorSpace, a film under another, and the space restored by AttributeEnd. In
// spectral mode the light's RGB is lifted in its space and the sensor writes the film's space:
// the image mean against that, with the wavelengths' noise (expectSpectralMean).
TEST(ColorSpace, SceneFilesUseTheSpaceInEffect) {
    const bool spectral = test::defaultSpectral();
    const RGBColorSpace &srgb = srgbColorSpace(), &aces = *namedColorSpace("aces2065-1"),
                        &rec2020 = *namedColorSpace("rec2020");
    // The sky's mean; `rgb` of `space` is its light, `film` the film's space, `expected` the RGB
    // mode's answer (to `tol`).
    auto check = [&](const std::string& beforeFilm, const std::string& world, std::array<float, 3> rgb,
                     const RGBColorSpace& space, const RGBColorSpace& film, Spectrum expected, float tol,
                     const char* what) {
        const std::string text = beforeFilm + R"(
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
Sampler "independent" "integer pixelsamples" [ 1 ]
WorldBegin
)" + world;
        const test::RegionStats s = test::wholeImage(test::renderString(text, spectral ? 16384 : 1).image);
        if (!spectral)
            return expectNear(Spectrum(float(s.mean[0]), float(s.mean[1]), float(s.mean[2])), expected, tol, what);
        const test::Lifted L = test::emission(rgb, space);
        test::expectSpectralMean(s, test::sensorRGB(Sensor::create({}, film).sensor, [&](double l) { return L.at(l); }),
                                 what);
    };
    const Spectrum acesWhite = chromaticityToRGB(0.32168, 0.33767);
    check("", "ColorSpace \"aces2065-1\"\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n", {1, 1, 1}, aces, srgb,
          acesWhite, 2e-3f, "sky written in ACES, sRGB film");
    check("", "AttributeBegin\nColorSpace \"aces2065-1\"\nAttributeEnd\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n",
          {1, 1, 1}, srgb, srgb, {1, 1, 1}, 1e-5f, "ACES set inside an attribute block");
    check("ColorSpace \"rec2020\"", "ColorSpace \"srgb\"\nLightSource \"infinite\" \"rgb L\" [ 1 0 0 ]\n", {1, 0, 0}, srgb,
          rec2020, {0.6274f, 0.0691f, 0.0164f}, 2e-3f, "sRGB red sky, BT.2020 film");
    check("ColorSpace \"rec2020\"", "LightSource \"infinite\" \"rgb L\" [ 0.5 0.4 0.3 ]\n", {0.5f, 0.4f, 0.3f}, rec2020,
          rec2020, {0.5f, 0.4f, 0.3f}, 1e-4f, "BT.2020 sky, BT.2020 film");
    // An unknown name warns and keeps the space in effect.
    check("", "ColorSpace \"aces2065-1\"\nColorSpace \"nonsense\"\nLightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n",
          {1, 1, 1}, aces, srgb, acesWhite, 2e-3f, "unknown name after ACES");
}
