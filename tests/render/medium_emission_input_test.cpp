// The emission inputs of the grid media, as pbrt-v4 defines them: "rgbgrid" "Le" (a grid of
// RGB illuminants times "Lescale") and the "nanovdb" temperature grid (Lescale times the
// peak-normalised blackbody of (value - temperatureoffset) * temperaturescale kelvin).
// A constant grid emits exactly what the equivalent homogeneous medium does, in both colour
// modes; a constant rgbgrid around the camera renders the exact glow of
// medium_emission_test.cpp; bad input is a located error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "media/nanovdb_medium.h"
#include "medium_emission_scenes.h"

using namespace ps;
using namespace ps::test;

namespace {

const std::string kNvdb = PATHSPACE_SOURCE_DIR "/tests/data/media/tiny.nvdb";

// Every coefficient of the two media at `p`, in RGB mode and at a few sets of wavelengths,
// equal to single-precision rounding.
void expectSameProperties(const std::string& a, const std::string& b, Vec3 p) {
    for (bool spectral : {false, true}) {
        auto sa = sceneInMedium(a, spectral), sb = sceneInMedium(b, spectral);
        ASSERT_TRUE(sa->cameraMedium()->emissive());
        ASSERT_TRUE(sb->cameraMedium()->emissive());
        for (int k = 0; k < (spectral ? 8 : 1); ++k) {
            const SampledWavelengths lambda = SampledWavelengths::sampleVisible((k + 0.5f) / 8);
            const SampledWavelengths* l = spectral ? &lambda : nullptr;
            const MediumProperties x = sa->cameraMedium()->at(p, l), y = sb->cameraMedium()->at(p, l);
            for (int c = 0; c < 4; ++c) {
                EXPECT_NEAR(x.sigmaA[c], y.sigmaA[c], 1e-5f * std::fabs(y.sigmaA[c]) + 1e-7f) << "sigma_a " << c;
                EXPECT_NEAR(x.sigmaS[c], y.sigmaS[c], 1e-5f * std::fabs(y.sigmaS[c]) + 1e-7f) << "sigma_s " << c;
                EXPECT_NEAR(x.Le[c], y.Le[c], 2e-5f * std::fabs(y.Le[c]) + 1e-7f) << "Le " << c << " spectral " << spectral;
                EXPECT_GT(y.Le[c], 0) << c;
            }
        }
    }
}

// A 4^3 grid over [-2, 2]^3 of one RGB value per parameter: constant over [-1.5, 1.5]^3,
// where trilinear lookups blend real voxels only.
std::string constantRgbGrid(const std::string& sigmaA, const std::string& le, const std::string& extra = "") {
    std::string a, l;
    for (int i = 0; i < 64; ++i) {
        a += sigmaA + "  ";
        l += le + "  ";
    }
    return R"("string type" "rgbgrid" "integer nx" [ 4 ] "integer ny" [ 4 ] "integer nz" [ 4 ]
  "point3 p0" [ -2 -2 -2 ] "point3 p1" [ 2 2 2 ] "rgb sigma_a" [ )" + a + R"( ] "rgb Le" [ )" + l + " ] " + extra;
}

}  // namespace

TEST(MediumEmissionInput, ConstantRgbGridEmitsAsHomogeneous) {
    expectSameProperties(constantRgbGrid("0.5 1 2", "1 0.8 0.6", "\"float Lescale\" [ 3 ] \"rgb sigma_s\" [ " +
                                             [] {
                                                 std::string s;
                                                 for (int i = 0; i < 64; ++i) s += "0.2 0.1 0.3  ";
                                                 return s;
                                             }() + " ]"),
                         R"("string type" "homogeneous" "rgb sigma_a" [ 0.5 1 2 ] "rgb sigma_s" [ 0.2 0.1 0.3 ]
                            "rgb Le" [ 1 0.8 0.6 ] "float Lescale" [ 3 ])",
                         Vec3(0.3f, -0.7f, 1.1f));
}

// pbrt-v4: T = (value - temperatureoffset) * temperaturescale; Le = Lescale B_T(lambda) / max B_T.
// The file's "smoke" grid is 0.5 everywhere around (10, 10, 10): density 0.5, and as the
// temperature grid T = (0.5 - 0.1) * 5000 = 2000 K.
// A homogeneous medium's Le is normalised to luminance 1, so its Lescale carries B_T's luminance.
TEST(MediumEmissionInput, ConstantTemperatureGridEmitsAsHomogeneousBlackbody) {
    const float T = (0.5f - 0.1f) * 5000.0f;
    const double luminance = SpectrumSource::blackbody(T).photometric();
    char homogeneous[256];
    std::snprintf(homogeneous, sizeof homogeneous,
                  R"("string type" "homogeneous" "rgb sigma_a" [ 0.5 0.5 0.5 ] "rgb sigma_s" [ 0.5 0.5 0.5 ]
                     "blackbody Le" [ %.9g ] "float Lescale" [ %.9g ])",
                  double(T), 0.01 * luminance);
    expectSameProperties("\"string type\" \"nanovdb\" \"string filename\" \"" + kNvdb +
                             R"(" "string gridname" "smoke" "string temperaturename" "smoke" "float temperatureoffset" [ 0.1 ]
                              "rgb sigma_a" [ 1 1 1 ] "rgb sigma_s" [ 1 1 1 ]
                              "float temperaturescale" [ 5000 ] "float Lescale" [ 0.01 ])",
                         homogeneous, Vec3(10, 10.3f, 9.6f));
}

// The older name "temperaturecutoff" is pbrt-v4's fallback for the offset; 100 K and below
// emit nothing; Lescale 0 turns emission off (not emissive at all).
TEST(MediumEmissionInput, TemperatureCutoffColdAndOff) {
    const std::string base = "\"string type\" \"nanovdb\" \"string filename\" \"" + kNvdb +
                             "\" \"string gridname\" \"smoke\" \"string temperaturename\" \"smoke\" ";
    auto medium = [&](const std::string& extra) { return sceneInMedium(base + extra, false); };
    auto cutoff = medium("\"float temperaturecutoff\" [ 0.1 ] \"float temperaturescale\" [ 5000 ]");
    auto offset = medium("\"float temperatureoffset\" [ 0.1 ] \"float temperaturescale\" [ 5000 ]");
    const Vec3 p(10, 10, 10);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(cutoff->cameraMedium()->at(p, nullptr).Le[c], offset->cameraMedium()->at(p, nullptr).Le[c]);
    EXPECT_FALSE(cutoff->cameraMedium()->at(p, nullptr).Le.isBlack());
    // (0.5 - 0) * 200 = 100 K: not above pbrt-v4's 100 K threshold (nor visible anyway);
    // 1000 K glows, faintly.
    EXPECT_TRUE(medium("\"float temperaturescale\" [ 200 ]")->cameraMedium()->at(p, nullptr).Le.isBlack());
    EXPECT_FALSE(medium("\"float temperaturescale\" [ 2000 ]")->cameraMedium()->at(p, nullptr).Le.isBlack());
    EXPECT_FALSE(medium("\"float Lescale\" [ 0 ]")->cameraMedium()->emissive());
    // Without a temperature grid in the file (the default name), no emission, as pbrt-v4.
    EXPECT_FALSE(sceneInMedium("\"string type\" \"nanovdb\" \"string filename\" \"" + kNvdb + "\"", false)
                     ->cameraMedium()
                     ->emissive());
}

// The constant rgbgrid filling the camera's sphere renders medium_emission_test.cpp's exact
// glow Le (1 - exp(-sigma_a)), in path and bdpt.
TEST(MediumEmissionInput, ConstantRgbGridRendersTheExactGlow) {
    std::string zero;
    for (int i = 0; i < 64; ++i) zero += "0 0 0  ";
    const std::string medium = constantRgbGrid("0.5 1 2", "1 0.8 0.6", "\"rgb sigma_s\" [ " + zero + " ]");
    const auto exact = glowingSphereExact(defaultSpectral());
    // The rgbgrid's Le is the RGB illuminant itself (pbrt-v4's RGBIlluminantSpectrum): luminance
    // normalised through the colour space's illuminant, as "rgb L" of a light and "rgb Le" of
    // the homogeneous medium.
    for (const char* name : {"path", "bdpt"}) expectRendersMatch(glowingSphere(name, 5, medium), name, 64, 16, exact);
}

TEST(MediumEmissionInput, BadInputIsALocatedError) {
    auto expectError = [](const std::string& text, const std::string& where, const std::string& what) {
        const std::string e = buildError(text);
        EXPECT_NE(e.find(where), std::string::npos) << e;
        EXPECT_NE(e.find(what), std::string::npos) << e;
    };
    // rgbgrid: an "Le" grid of another size, "Le" without sigma_a, a negative Lescale.
    expectError("WorldBegin\nMakeNamedMedium \"g\" \"string type\" \"rgbgrid\" \"integer nx\" [ 2 ]\n"
                "  \"rgb sigma_a\" [ 1 1 1  1 1 1 ] \"rgb Le\" [ 1 1 1 ]\n",
                "scene.pbrt:2:1", "1 \"Le\" values; expected nx*ny*nz = 2*1*1 = 2");
    expectError("WorldBegin\nMakeNamedMedium \"g\" \"string type\" \"rgbgrid\" \"rgb sigma_s\" [ 1 1 1 ] \"rgb Le\" [ 1 1 1 ]\n",
                "scene.pbrt:2:1", "\"Le\" needs a \"sigma_a\" grid");
    expectError("WorldBegin\nMakeNamedMedium \"g\" \"string type\" \"rgbgrid\" \"rgb sigma_a\" [ 1 1 1 ] \"rgb Le\" [ 1 1 1 ]\n"
                "  \"float Lescale\" [ -1 ]\n",
                "scene.pbrt:2:1", "\"Lescale\" must be a finite number at least 0");
    expectError("WorldBegin\nMakeNamedMedium \"g\" \"string type\" \"rgbgrid\" \"rgb sigma_a\" [ 1 1 1 ] \"rgb Le\" [ 1 -1 1 ]\n",
                "scene.pbrt:2:1", "\"Le\" values must not be negative");
    // nanovdb: a temperature grid named but absent, a negative Lescale.
    const std::string nvdb = "WorldBegin\nMakeNamedMedium \"v\" \"string type\" \"nanovdb\" \"string filename\" \"" + kNvdb + "\"\n  ";
    expectError(nvdb + "\"string temperaturename\" \"heat\"\n", "scene.pbrt:2:1",
                "has no grid named \"heat\" (\"temperaturename\")");
    expectError(nvdb + "\"float Lescale\" [ -2 ]\n", "scene.pbrt:2:1", "\"Lescale\" must be a finite number at least 0");
}
