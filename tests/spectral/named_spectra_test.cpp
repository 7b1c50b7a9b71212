#include <gtest/gtest.h>

#include <cmath>

#include "spectral/cie.h"
#include "spectral/named_spectra.h"
#include "spectral/optical_constants_data.h"

using namespace ps;

namespace {

const char* const kGlasses[] = {"glass-BK7", "glass-BAF10", "glass-FK51A", "glass-LASF9", "glass-F5", "glass-F10", "glass-F11"};

}  // namespace

// The Sellmeier formula with SCHOTT's coefficients gives the catalogue index at the d line.
TEST(NamedSpectra, SellmeierMatchesCatalogueNd) {
    EXPECT_NEAR(sellmeierGlass("glass-BK7")->index(587.56), 1.5168, 1e-5);
    for (const char* g : kGlasses) EXPECT_NEAR(sellmeierGlass(g)->index(587.56), sellmeierGlass(g)->nd, 1e-5) << g;
}

// pbrt-v4's glass tables are those Sellmeier curves sampled at wavelengths printed truncated
// to whole nm: each tabulated value lies between the formula at lambda and at lambda + 1
// (the truncation hides up to 4e-4 of index, so an exact match at the printed wavelength is
// not expected). Between the samples, linear interpolation of the table stays within 4e-4
// of the formula over the visible range.
TEST(NamedSpectra, GlassTablesAreTheSellmeierCurves) {
    for (const char* g : kGlasses) {
        const SellmeierGlass* s = sellmeierGlass(g);
        const auto pairs = opticalConstantPairs(g);
        ASSERT_GT(pairs.size(), 40u) << g;
        for (size_t i = 0; i < pairs.size(); i += 2) {
            const double hi = s->index(pairs[i]), lo = s->index(pairs[i] + 1.0);  // n decreases with lambda
            EXPECT_GE(pairs[i + 1], lo - 2e-7) << g << " at " << pairs[i];
            EXPECT_LE(pairs[i + 1], hi + 2e-7) << g << " at " << pairs[i];
        }
        const SpectrumSource n = *namedSpectrum(g);
        for (float l = 400; l <= 800; l += 7) EXPECT_NEAR(n.at(l), s->index(l), 4e-4) << g << " at " << l;
        EXPECT_NEAR(n.at(587.56f), s->nd, 4e-4) << g;
    }
}

// Metal tables are used as tabulated: values at sample wavelengths equal the source table
// (Palik's via pbrt-v4), and are linear in between.
TEST(NamedSpectra, MetalTablesAtTheirSamples) {
    struct Case {
        const char* name;
        float lambda, value;
    };
    for (const Case& c : {Case{"metal-Au-eta", 590.400818f, 0.236f}, Case{"metal-Cu-k", 563.564453f, 2.599f},
                          Case{"metal-Ag-k", 450.851562f, 2.478750f}, Case{"metal-CuZn-eta", 550, 0.527f},
                          Case{"metal-CuZn-k", 550, 2.765f}, Case{"metal-Al-eta", 413.280579f, 0.523f},
                          Case{"metal-TiO2-eta", 600.097046f, 2.9f}, Case{"metal-MgO-eta", 589.258972f, 1.73737f}}) {
        const auto s = namedSpectrum(c.name);
        ASSERT_TRUE(s) << c.name;
        EXPECT_NEAR(s->at(c.lambda), c.value, 1e-5f) << c.name;
    }
    const SpectrumSource cuzn = *namedSpectrum("metal-CuZn-eta");
    EXPECT_NEAR(cuzn.at(555), 0.5 * (0.527f + 0.505f), 1e-6);
    for (const char* m : {"Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"})
        for (const char* part : {"-eta", "-k"}) EXPECT_TRUE(namedSpectrum(std::string("metal-") + m + part)) << m << part;
    EXPECT_FALSE(namedSpectrum("metal-Fe-eta"));
    EXPECT_FALSE(namedSpectrum("glass-bk7"));  // case-sensitive, as pbrt-v4
}

// Named tables are extended flat to the visible range (pbrt's FromInterleaved): the F
// illuminants (380-780 nm) hold their end values at 360 and 830 nm; MgO (310-768 nm) too.
TEST(NamedSpectra, TablesExtendedToTheVisibleRange) {
    const SpectrumSource f1 = *namedSpectrum("stdillum-F1");
    EXPECT_GT(f1.at(365), 0.0f);
    EXPECT_FLOAT_EQ(f1.at(365), f1.at(380));
    EXPECT_FLOAT_EQ(f1.at(830), f1.at(780));
    EXPECT_FLOAT_EQ(namedSpectrum("metal-MgO-eta")->at(830), namedSpectrum("metal-MgO-eta")->at(767.677979f));
    // Inline piecewise-linear spectra are not extended: zero outside their samples.
    const SpectrumSource inl = SpectrumSource::piecewiseLinear({400, 700}, {1, 2});
    EXPECT_EQ(inl.at(399), 0.0f);
    EXPECT_FLOAT_EQ(inl.at(550), 1.5f);
    EXPECT_EQ(inl.at(701), 0.0f);
}

// Illuminants are normalised to luminance 1 (sum ybar s = the Y integral), keeping their
// published chromaticities (CIE 015:2004 table T.3 / T.8: A, D65, D50, F2, F11).
TEST(NamedSpectra, IlluminantsNormalisedWithTheirChromaticity) {
    struct Case {
        const char* name;
        double x, y;
    };
    for (const Case& c : {Case{"stdillum-A", 0.44758, 0.40745}, Case{"stdillum-D65", 0.31272, 0.32903},
                          Case{"stdillum-D50", 0.33681, 0.35798}, Case{"stdillum-F2", 0.37208, 0.37529},
                          Case{"stdillum-F11", 0.38052, 0.37713}, Case{"illum-acesD60", 0.32168, 0.33767}}) {
        const SpectrumSource s = *namedSpectrum(c.name);
        const XYZ xyz = spectrumToXYZ(s);
        EXPECT_NEAR(xyz[1], 1.0, 1e-5) << c.name;
        const double sum = xyz[0] + xyz[1] + xyz[2];
        EXPECT_NEAR(xyz[0] / sum, c.x, 1e-3) << c.name;
        EXPECT_NEAR(xyz[1] / sum, c.y, 1e-3) << c.name;
        EXPECT_NEAR(s.photometric(), kCieYIntegral, 1e-3) << c.name;
    }
}

// The matching functions: the Y sum is the Y integral, and the equal-energy white is
// (1/3, 1/3) (CIE 015: x_E = y_E = 1/3 to 1e-4).
TEST(NamedSpectra, CieTables) {
    double x = 0, y = 0, z = 0;
    for (int i = 0; i < kCieSamples; ++i) {
        x += kCieX[i];
        y += kCieY[i];
        z += kCieZ[i];
    }
    EXPECT_NEAR(y, kCieYIntegral, 1e-4);
    EXPECT_NEAR(x / (x + y + z), 1.0 / 3, 1e-4);
    EXPECT_NEAR(y / (x + y + z), 1.0 / 3, 1e-4);
    EXPECT_FLOAT_EQ(denseLookup(kCieY, 555.4f), 1.0f);  // the peak of ybar at 555 nm
    EXPECT_EQ(denseLookup(kCieY, 359.4f), 0.0f);
}
