#include <gtest/gtest.h>

#include <cmath>

#include "spectral/spectrum_source.h"

using namespace ps;

TEST(Blackbody, PeakNormalisedAtWiensWavelength) {
    for (float T : {2700.0f, 5000.0f, 6500.0f}) {
        const SpectrumSource bb = SpectrumSource::blackbody(T);
        const float peak = 2.8977721e-3f / T * 1e9f;
        EXPECT_NEAR(bb.at(peak), 1.0f, 1e-5f) << T;
        EXPECT_LT(bb.at(peak - 20), 1.0f);
        EXPECT_LT(bb.at(peak + 20), 1.0f);
        EXPECT_EQ(bb.maxValue(), 1.0f);
    }
}

// CIE 1931 chromaticities of the Planckian radiator (e.g. CIE 015:2004 and the Planckian
// locus tables of Wyszecki & Stiles): 2700 K (0.4599, 0.4106), 6500 K (0.3135, 0.3236).
TEST(Blackbody, ChromaticityOnThePlanckianLocus) {
    struct Case {
        float T;
        double x, y;
    };
    for (const Case& c : {Case{2700, 0.45986, 0.41060}, Case{6500, 0.31352, 0.32363}}) {
        const XYZ xyz = spectrumToXYZ(SpectrumSource::blackbody(c.T));
        const double s = xyz[0] + xyz[1] + xyz[2];
        EXPECT_NEAR(xyz[0] / s, c.x, 2e-4) << c.T;
        EXPECT_NEAR(xyz[1] / s, c.y, 2e-4) << c.T;
    }
}
