#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "spectral/cie.h"
#include "spectral/spectrum_source.h"
#include "spectral/wavelengths.h"

using namespace ps;

TEST(Wavelengths, VisiblePdfIntegratesToOne) {
    // Simpson's rule on a fine grid: the density is smooth, so this is exact to ~1e-10.
    const int n = 47000;
    const double h = (kLambdaMax - kLambdaMin) / double(n);
    double sum = 0;
    for (int i = 0; i <= n; ++i) {
        const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        sum += w * visibleWavelengthPdf(float(kLambdaMin + i * h));
    }
    EXPECT_NEAR(sum * h / 3, 1.0, 1e-5);
    EXPECT_EQ(visibleWavelengthPdf(359.9f), 0.0f);
    EXPECT_EQ(visibleWavelengthPdf(830.1f), 0.0f);
    // pbrt-v4's closed form (sampling.h: VisibleWavelengthsPDF) up to its rounded constant.
    EXPECT_NEAR(visibleWavelengthPdf(538), 0.0039398042f, 1e-7);
}

TEST(Wavelengths, SampleVisibleFollowsItsPdf) {
    // Chi-square of 2^20 samples of lambda[0] (u uniform) in 47 bins of 10 nm against the
    // integrated density. Critical value of chi^2 with 46 dof at p = 1e-4: 88.
    const int nBins = 47, n = 1 << 20;
    std::vector<double> count(nBins, 0), expected(nBins, 0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u01(0, 1);
    for (int i = 0; i < n; ++i) {
        const float l = SampledWavelengths::sampleVisible(u01(rng)).lambda[0];
        count[std::min(nBins - 1, int((l - kLambdaMin) / 10))] += 1;
    }
    for (int b = 0; b < nBins; ++b)
        for (int k = 0; k < 1000; ++k) expected[b] += visibleWavelengthPdf(kLambdaMin + 10 * b + (k + 0.5f) * 0.01f) * 0.01 * n;
    double chi2 = 0;
    for (int b = 0; b < nBins; ++b) chi2 += (count[b] - expected[b]) * (count[b] - expected[b]) / expected[b];
    EXPECT_LT(chi2, 88.0);
}

TEST(Wavelengths, StratifiedOffsetsAndPdfs) {
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.9f);
    // lambda[i] is the quantile of (u + i/4) mod 1: increasing after the wrap at i = 1.
    EXPECT_NEAR(w.lambda[0], sampleVisibleWavelength(0.9f), 1e-4);
    EXPECT_NEAR(w.lambda[1], sampleVisibleWavelength(0.15f), 1e-3);
    EXPECT_NEAR(w.lambda[3], sampleVisibleWavelength(0.65f), 1e-3);
    for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(w.pdf[i], visibleWavelengthPdf(w.lambda[i]));

    const SampledWavelengths uw = SampledWavelengths::sampleUniform(0.5f);
    EXPECT_FLOAT_EQ(uw.lambda[0], 595);
    EXPECT_FLOAT_EQ(uw.lambda[1], 712.5f);
    EXPECT_FLOAT_EQ(uw.lambda[2], 830);
    EXPECT_FLOAT_EQ(uw.lambda[3], 477.5f);  // 947.5 wrapped around to 360 + 117.5
    EXPECT_FLOAT_EQ(uw.pdf[3], 1.0f / 470);
}

// The spectral estimate of the Y of a flat spectrum (sum over the 1 nm grid of ybar = the
// Y integral) is unbiased with the wavelengths' pdfs, also after terminating the secondary
// wavelengths. Within 4 standard errors.
TEST(Wavelengths, UnbiasedYEstimateWithAndWithoutTermination) {
    for (bool terminate : {false, true}) {
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> u01(0, 1);
        const int n = 200000;
        double sum = 0, sum2 = 0;
        for (int i = 0; i < n; ++i) {
            SampledWavelengths w = SampledWavelengths::sampleVisible(u01(rng));
            if (terminate) w.terminateSecondary();
            double est = 0;
            for (int k = 0; k < kWavelengthSamples; ++k)
                if (w.pdf[k] != 0) est += denseLookup(kCieY, w.lambda[k]) * 1.0 / w.pdf[k];
            est /= kWavelengthSamples;
            sum += est;
            sum2 += est * est;
        }
        const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
        // The exact integral of the nearest-nm lookup: each 1 nm cell holds one table value,
        // the end cells half of one.
        double exact = 0;
        for (int i = 0; i < kCieSamples; ++i) exact += kCieY[i] * ((i == 0 || i == kCieSamples - 1) ? 0.5 : 1.0);
        EXPECT_LT(std::fabs(mean - exact), 4 * se) << "terminate " << terminate << " mean " << mean << " exact " << exact;
        EXPECT_LT(se, 0.01 * exact);
    }
}

TEST(Wavelengths, TerminateSecondaryKeepsTheFirst) {
    SampledWavelengths w = SampledWavelengths::sampleVisible(0.3f);
    const SampledWavelengths before = w;
    EXPECT_FALSE(w.secondaryTerminated());
    w.terminateSecondary();
    EXPECT_TRUE(w.secondaryTerminated());
    EXPECT_EQ(w.lambda, before.lambda);
    EXPECT_FLOAT_EQ(w.pdf[0], before.pdf[0] / 4);
    for (int i = 1; i < 4; ++i) EXPECT_EQ(w.pdf[i], 0.0f);
    w.terminateSecondary();  // idempotent
    EXPECT_FLOAT_EQ(w.pdf[0], before.pdf[0] / 4);
}
