#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "spectral/rgb_to_spectrum.h"
#include "spectral_test_util.h"

using namespace ps;
using namespace ps::test;

namespace {

struct RoundTripError {
    double max = 0, mean = 0;
};

// Lifts a grid of RGB (saturated corners included) through the space's table and integrates
// back under its illuminant; the largest and mean of the per-colour max |RGB error|.
RoundTripError roundTrip(const RGBColorSpace& space, int n) {
    RoundTripError e;
    int count = 0;
    for (int r = 0; r < n; ++r)
        for (int g = 0; g < n; ++g)
            for (int b = 0; b < n; ++b) {
                const std::array<float, 3> rgb{float(r) / (n - 1), float(g) / (n - 1), float(b) / (n - 1)};
                const auto back = reflectanceRGB(SpectrumSource::rgbAlbedo(space, rgb), space);
                double err = 0;
                for (int c = 0; c < 3; ++c) err = std::max(err, std::fabs(back[c] - rgb[c]));
                e.max = std::max(e.max, err);
                e.mean += err;
                ++count;
            }
    e.mean /= count;
    return e;
}

}  // namespace

// The table's accuracy per colour space over an 11^3 grid of RGB in [0,1]^3. Every sRGB colour
// is a reflectance colour, so sRGB's error is the fit's. The wider spaces' saturated corners
// are not: no reflectance under D65 is as saturated as P3's red or green primary at their
// luminance (the red comes back at 0.78), Rec.2020's red lies near the spectral locus (a
// step reflectance, the most saturated red there is, gives 0.39), and ACES AP0's primaries lie
// outside the locus altogether. There the optimum misses by the gamut's distance, so the
// bounds below are the measured errors (2 decimals) plus a margin; a broken table or
// lookup exceeds the means.
TEST(RgbToSpectrum, AlbedoRoundTripPerColourSpace) {
    struct Case {
        const char* space;
        double maxErr, meanErr;
    };
    for (const Case& c : {Case{"srgb", 1e-3, 3e-4}, Case{"dci-p3", 0.25, 5e-3}, Case{"rec2020", 0.65, 0.035},
                          Case{"aces2065-1", 0.8, 0.15}}) {
        const RoundTripError e = roundTrip(*namedColorSpace(c.space), 11);
        std::printf("[ round trip ] %-10s max %.2e mean %.2e\n", c.space, e.max, e.mean);
        EXPECT_LT(e.max, c.maxErr) << c.space;
        EXPECT_LT(e.mean, c.meanErr) << c.space;
    }
}

// Colours inside every space's reflectance gamut (sRGB colours away from its boundary,
// expressed in each space) round-trip to the fit's precision plus the table's interpolation
// error, in every space.
TEST(RgbToSpectrum, InteriorColoursAreAccurateInEverySpace) {
    const Matrix3& xyzFromSrgb = colorimetry(srgbColorSpace()).xyzFromRGB;
    for (int s = 0; s < kNamedColorSpaces; ++s) {
        const RGBColorSpace& space = colorSpaceByIndex(s);
        const Matrix3 toSpace = colorimetry(space).rgbFromXYZ * xyzFromSrgb;
        double maxErr = 0;
        for (double r : {0.2, 0.45, 0.7})
            for (double g : {0.25, 0.5, 0.65})
                for (double b : {0.3, 0.55, 0.6}) {
                    const auto v = toSpace * std::array<double, 3>{r, g, b};
                    const std::array<float, 3> rgb{float(v[0]), float(v[1]), float(v[2])};
                    const auto back = reflectanceRGB(SpectrumSource::rgbAlbedo(space, rgb), space);
                    for (int c = 0; c < 3; ++c) maxErr = std::max(maxErr, std::fabs(back[c] - rgb[c]));
                }
        std::printf("[ interior   ] %-10s max %.2e\n", space.name, maxErr);
        EXPECT_LT(maxErr, 1e-3) << space.name;
    }
}

// Black, white and greys are special-cased to constant spectra: exact in every space.
TEST(RgbToSpectrum, GreysAreExact) {
    for (int s = 0; s < kNamedColorSpaces; ++s) {
        const RGBColorSpace& space = colorSpaceByIndex(s);
        for (float v : {0.0f, 0.18f, 0.5f, 0.9f, 1.0f}) {
            const SpectrumSource sp = SpectrumSource::rgbAlbedo(space, {v, v, v});
            for (float l : {360.0f, 500.0f, 700.0f, 830.0f}) EXPECT_NEAR(sp.at(l), v, 1e-6f) << space.name << " " << v;
            const auto back = reflectanceRGB(sp, space);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], v, 1e-5) << space.name << " " << v;
        }
        EXPECT_EQ(SpectrumSource::rgbAlbedo(space, {0, 0, 0}).at(550), 0.0f);
        EXPECT_EQ(SpectrumSource::rgbAlbedo(space, {1, 1, 1}).at(550), 1.0f);
        EXPECT_EQ(SpectrumSource::rgbAlbedo(space, {std::nanf(""), 0, 0}).at(550), 0.0f);
    }
}

// The unbounded form is scale * S(rgb / scale), scale = 2 max: the polynomial of the colour
// at half brightness, so it reproduces the RGB up to the table error times the scale.
TEST(RgbToSpectrum, UnboundedAndIlluminantScale) {
    const RGBColorSpace& srgb = srgbColorSpace();
    const std::array<float, 3> rgb{2.4f, 1.0f, 0.3f};
    const SpectrumSource u = SpectrumSource::rgbUnbounded(srgb, rgb);
    const SpectrumSource half = SpectrumSource::rgbAlbedo(srgb, {0.5f, 1.0f / 4.8f, 0.3f / 4.8f});
    for (float l : {400.0f, 550.0f, 700.0f}) EXPECT_NEAR(u.at(l), 4.8f * half.at(l), 1e-5f);
    EXPECT_NEAR(u.maxValue(), 4.8f * half.maxValue(), 1e-5f);
    const auto back = reflectanceRGB(u, srgb);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], rgb[c], 4.8 * 2e-3) << c;

    // The illuminant form is the unbounded one times the space's illuminant.
    const SpectrumSource i = SpectrumSource::rgbIlluminant(srgb, rgb);
    const DenseSpectrum& d65 = colorimetry(srgb).illuminant;
    for (float l : {400.0f, 550.5f, 700.2f}) EXPECT_NEAR(i.at(l), u.at(l) * d65.at(l), 1e-4f * i.at(l));
    // Its photometric integral is the illuminant's alone (the RGB is a multiplier).
    EXPECT_NEAR(i.photometric(), SpectrumSource::rgbIlluminant(srgb, {1, 1, 1}).photometric(), 1e-9);
    EXPECT_NEAR(i.photometric(), kCieYIntegral, 1e-3);
    EXPECT_EQ(SpectrumSource::rgbUnbounded(srgb, {0, 0, 0}).at(500), 0.0f);
}

// The embedded bytes are the generator's (a wrong .incbin path, order or truncation fails).
TEST(RgbToSpectrum, EmbeddedTablesMatchTheGenerator) {
    for (int s = 0; s < kNamedColorSpaces; ++s) {
        const RGBToSpectrumTable& t = RGBToSpectrumTable::forSpace(colorSpaceByIndex(s));
        EXPECT_EQ(t.checksum(), t.expectedChecksum()) << colorSpaceByIndex(s).name;
    }
}

// pbrt-v4's colour spaces take their white from the illuminant spectrum: sRGB's is D65's
// (0.3127, 0.3290) to 1e-4, and RGB (1,1,1) is that white at Y = 1.
TEST(RgbToSpectrum, ColourSpaceWhiteFromItsIlluminant) {
    for (int s = 0; s < kNamedColorSpaces; ++s) {
        const RGBColorSpace& space = colorSpaceByIndex(s);
        const Colorimetry& c = colorimetry(space);
        EXPECT_NEAR(c.white[0], space.white[0], 2e-4) << space.name;
        EXPECT_NEAR(c.white[1], space.white[1], 2e-4) << space.name;
        const auto w = c.xyzFromRGB * XYZ{1, 1, 1};
        EXPECT_NEAR(w[1], 1.0, 1e-6) << space.name;
        EXPECT_NEAR(w[0] / (w[0] + w[1] + w[2]), c.white[0], 1e-9);
    }
}
