#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "scene/spectra.h"

using namespace ps;

namespace {

// CIE D65 at 10 nm, 380-780 nm: an independent copy for the tests.
const std::vector<float> kD65 = {49.98f, 54.65f, 82.75f, 91.49f, 93.43f, 86.68f, 104.87f, 117.01f, 117.81f, 114.86f, 115.92f,
                                 108.81f, 109.35f, 107.80f, 104.79f, 107.69f, 104.41f, 104.05f, 100.00f, 96.33f, 95.79f, 88.69f,
                                 90.01f, 89.60f, 87.70f, 83.29f, 83.70f, 80.03f, 80.21f, 82.28f, 78.28f, 69.72f, 71.61f, 74.35f,
                                 61.60f, 69.89f, 75.09f, 63.59f, 46.42f, 66.81f, 63.38f};

std::vector<float> d65Lambdas() {
    std::vector<float> l;
    for (int i = 0; i < 41; ++i) l.push_back(380.0f + 10 * i);
    return l;
}

void expectRGB(const Spectrum& s, float r, float g, float b, float tol) {
    EXPECT_NEAR(s.r, r, tol);
    EXPECT_NEAR(s.g, g, tol);
    EXPECT_NEAR(s.b, b, tol);
}

}  // namespace

TEST(Spectra, FlatReflectanceIsWhite) {
    expectRGB(sampledSpectrumToRGB({300, 900}, {1, 1}, SpectrumKind::Albedo), 1, 1, 1, 1e-2);
    expectRGB(sampledSpectrumToRGB({300, 900}, {0.3f, 0.3f}, SpectrumKind::Albedo), 0.3f, 0.3f, 0.3f, 1e-2);
    // Reflectances are clamped to [0, 1], per wavelength and per channel.
    expectRGB(sampledSpectrumToRGB({300, 900}, {5, 5}, SpectrumKind::Albedo), 1, 1, 1, 1e-2);
    Spectrum red = sampledSpectrumToRGB({380, 599, 600, 780}, {0, 0, 1, 1}, SpectrumKind::Albedo);
    EXPECT_GT(red.r, 0.5f);
    EXPECT_LT(red.b, 0.1f);
    EXPECT_GE(red.g, 0.0f);
    EXPECT_LE(red.r, 1.0f);
}

// Spectral emission keeps only its chromaticity, at luminance 1 (PBRT-CONVENTIONS §3).
TEST(Spectra, IlluminantsAreNormalisedToLuminanceOne) {
    Spectrum d65 = sampledSpectrumToRGB(d65Lambdas(), kD65, SpectrumKind::Illuminant);
    expectRGB(d65, 1, 1, 1, 1e-2);
    EXPECT_NEAR(d65.luminance(), 1, 1e-2);
    std::vector<float> scaled = kD65;
    for (float& v : scaled) v *= 37;
    Spectrum d65x = sampledSpectrumToRGB(d65Lambdas(), scaled, SpectrumKind::Illuminant);
    EXPECT_NEAR(d65x.g, d65.g, 1e-5);
    // "spectrum L" [400 10 700 10]: luminance 1 whatever the magnitude.
    EXPECT_NEAR(sampledSpectrumToRGB({400, 700}, {10, 10}, SpectrumKind::Illuminant).luminance(), 1, 0.03);
    // Nothing visible: black rather than a division by zero.
    EXPECT_TRUE(sampledSpectrumToRGB({1000, 1100}, {1, 1}, SpectrumKind::Illuminant).isBlack());
}

TEST(Spectra, Blackbody) {
    Spectrum bb = blackbodyToRGB(6500);
    EXPECT_NEAR(bb.luminance(), 1, 0.02);
    expectRGB(bb, 1, 1, 1, 0.1);  // 6500 K is close to the D65 white
    Spectrum warm = blackbodyToRGB(2700);
    EXPECT_NEAR(warm.luminance(), 1, 0.02);
    EXPECT_GT(warm.r, 2 * warm.b);
    Spectrum cold = blackbodyToRGB(12000);
    EXPECT_GT(cold.b, cold.r);
    // Not as emission: pbrt's peak-normalised curve, so within [0, 1] as a reflectance.
    Spectrum refl = blackbodyToRGB(5500, SpectrumKind::Albedo);
    EXPECT_GT(refl.g, 0.5f);
    EXPECT_LE(refl.maxComponent(), 1.0f);
    EXPECT_TRUE(blackbodyToRGB(-3).isBlack());
}

TEST(Spectra, UnboundedSpectraAreBandAverages) {
    expectRGB(sampledSpectrumToRGB({300, 900}, {1.5f, 1.5f}, SpectrumKind::Unbounded), 1.5f, 1.5f, 1.5f, 1e-4);
    // An index falling with wavelength (normal dispersion): blue > green > red, within the curve's range.
    Spectrum s = sampledSpectrumToRGB({400, 700}, {2, 1}, SpectrumKind::Unbounded);
    EXPECT_GT(s.b, s.g);
    EXPECT_GT(s.g, s.r);
    EXPECT_GE(s.r, 1.0f);
    EXPECT_LE(s.b, 2.0f);
}

TEST(Spectra, NamedSpectra) {
    auto cuEta = namedSpectrumToRGB("metal-Cu-eta", SpectrumKind::Unbounded);
    auto cuK = namedSpectrumToRGB("metal-Cu-k", SpectrumKind::Unbounded);
    ASSERT_TRUE(cuEta && cuK);
    // Not our own output: the RGB reduction of measured copper published with the Tungsten
    // renderer (B. Bitterli, src/core/bsdfs/ComplexIorData.hpp, entry "Cu"), which pbrt-v4
    // has no equivalent of (it evaluates its eta(lambda), k(lambda) curves per wavelength).
    expectRGB(*cuEta, 0.2004377f, 0.9240334f, 1.1022120f, 1e-5);
    expectRGB(*cuK, 3.9129485f, 2.4528477f, 2.1421880f, 1e-5);
    for (const char* m : {"Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"})
        for (const char* part : {"-eta", "-k"})
            EXPECT_TRUE(namedSpectrumToRGB(std::string("metal-") + m + part, SpectrumKind::Unbounded).has_value()) << m << part;
    auto bk7 = namedSpectrumToRGB("glass-BK7", SpectrumKind::Unbounded);
    ASSERT_TRUE(bk7);
    // Schott's Sellmeier formula for N-BK7 (catalogue coefficients) at the helium d line,
    // 587.5618 nm: the catalogue's n_d = 1.5168.
    const double B[3] = {1.03961212, 0.231792344, 1.01046945}, C[3] = {0.00600069867, 0.0200179144, 103.560653};
    const double l2 = 0.5875618 * 0.5875618;  // micrometres squared
    double n2 = 1;
    for (int i = 0; i < 3; ++i) n2 += B[i] * l2 / (l2 - C[i]);
    const float nd = float(std::sqrt(n2));
    expectRGB(*bk7, nd, nd, nd, 1e-4);
    for (const char* g : {"glass-BAF10", "glass-FK51A", "glass-LASF9", "glass-F5", "glass-F10", "glass-F11"}) {
        auto s = namedSpectrumToRGB(g, SpectrumKind::Unbounded);
        ASSERT_TRUE(s) << g;
        EXPECT_GT(s->r, 1.4f);
        EXPECT_LT(s->r, 1.9f);
        EXPECT_EQ(s->r, s->b);
    }
    auto d65 = namedSpectrumToRGB("stdillum-D65", SpectrumKind::Illuminant);
    ASSERT_TRUE(d65);
    expectRGB(*d65, 1, 1, 1, 1e-3);
    auto a = namedSpectrumToRGB("stdillum-A", SpectrumKind::Illuminant);
    ASSERT_TRUE(a);
    EXPECT_NEAR(a->luminance(), 1, 0.01);
    EXPECT_GT(a->r, 1.5f * a->b);
    auto d50 = namedSpectrumToRGB("stdillum-D50", SpectrumKind::Illuminant);
    ASSERT_TRUE(d50);
    EXPECT_NEAR(d50->luminance(), 1, 0.01);
    EXPECT_GT(d50->r, d50->b);
    for (int i = 1; i <= 12; ++i)
        EXPECT_TRUE(namedSpectrumToRGB("stdillum-F" + std::to_string(i), SpectrumKind::Illuminant).has_value()) << i;
    EXPECT_TRUE(namedSpectrumToRGB("illum-acesD60", SpectrumKind::Illuminant).has_value());
    EXPECT_FALSE(namedSpectrumToRGB("metal-Unobtainium-eta", SpectrumKind::Unbounded).has_value());
    EXPECT_FALSE(namedSpectrumToRGB("metal-Cu-x", SpectrumKind::Unbounded).has_value());
    EXPECT_FALSE(namedSpectrumToRGB("metal-", SpectrumKind::Unbounded).has_value());
    EXPECT_FALSE(namedSpectrumToRGB("stdillum-F13", SpectrumKind::Illuminant).has_value());
}

TEST(Spectra, ColourSpaceHelpers) {
    expectRGB(chromaticityToRGB(0.31271, 0.32902), 1, 1, 1, 1e-5);
    Spectrum white = xyzToLinearSRGB(0.95047, 1.0, 1.08883);
    expectRGB(white, 1, 1, 1, 1e-3);
}

TEST(Spectra, SpectrumFiles) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / ("pathspace-spd-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "ok.spd") << "# comment\n400 1 # inline comment\n500 2\r\n600 +3e0\n";
    std::ofstream(dir / "odd.spd") << "400 1 500";
    std::ofstream(dir / "down.spd") << "500 1 400 2";
    std::ofstream(dir / "junk.spd") << "400 abc";
    std::ofstream(dir / "empty.spd") << "# nothing\n";
    std::vector<float> l, v;
    EXPECT_EQ(readSpectrumFile((dir / "ok.spd").string(), l, v), "");
    EXPECT_EQ(l, (std::vector<float>{400, 500, 600}));
    EXPECT_EQ(v, (std::vector<float>{1, 2, 3}));
    for (const char* bad : {"odd.spd", "down.spd", "junk.spd", "empty.spd", "missing.spd"})
        EXPECT_NE(readSpectrumFile((dir / bad).string(), l, v), "") << bad;
    std::filesystem::remove_all(dir);
}
