#include <gtest/gtest.h>

#include <vector>

#include "mc/distribution.h"
#include "mc/rng.h"

using namespace ps;

// Chi-square of discrete samples against the table's probabilities.
TEST(Distribution1D, DiscreteSamplingMatchesWeights) {
    std::vector<float> w = {1, 0, 3, 2, 0.5f, 0, 4};
    Distribution1D d(w);
    float total = 0;
    for (float x : w) total += x;
    Rng rng(11);
    int n = 200000;
    std::vector<int> counts(w.size(), 0);
    for (int i = 0; i < n; ++i) {
        float pmf;
        int k = d.sampleDiscrete(rng.uniform(), &pmf);
        ASSERT_GT(w[k], 0.0f) << "zero-weight bin sampled";
        ASSERT_NEAR(pmf, w[k] / total, 1e-6f);
        ++counts[k];
    }
    double chi2 = 0;
    int dof = -1;
    for (size_t k = 0; k < w.size(); ++k) {
        if (w[k] == 0) continue;
        double e = n * w[k] / total;
        chi2 += (counts[k] - e) * (counts[k] - e) / e;
        ++dof;
    }
    EXPECT_LT(chi2, 22.46);  // chi-square(5 dof) at p = 0.999
    (void)dof;
}

TEST(Distribution1D, ContinuousPdfIntegratesToOneAndMatchesSamples) {
    std::vector<float> w = {0.5f, 2, 0, 1};
    Distribution1D d(w);
    double integral = 0;
    for (int i = 0; i < 4000; ++i) integral += d.pdf((i + 0.5f) / 4000) / 4000;
    EXPECT_NEAR(integral, 1.0, 1e-6);
    Rng rng(12);
    for (int i = 0; i < 1000; ++i) {
        float pdf;
        float x = d.sampleContinuous(rng.uniform(), &pdf);
        ASSERT_GE(x, 0.0f);
        ASSERT_LT(x, 1.0f);
        ASSERT_NEAR(pdf, d.pdf(x), 1e-5f);
        ASSERT_GT(pdf, 0.0f);
    }
}

TEST(Distribution1D, AllZeroBecomesUniform) {
    std::vector<float> w = {0, 0, 0};
    Distribution1D d(w);
    EXPECT_NEAR(d.pmf(1), 1.0f / 3, 1e-6f);
}

TEST(Distribution2D, SamplesFollowTheTable) {
    int nu = 4, nv = 3;
    std::vector<float> w = {1, 2, 3, 4, 0, 0, 1, 0, 5, 1, 1, 1};
    Distribution2D d(w, nu, nv);
    float total = 0;
    for (float x : w) total += x;
    Rng rng(13);
    int n = 200000;
    std::vector<int> counts(w.size(), 0);
    for (int i = 0; i < n; ++i) {
        float pdf;
        Vec2 p = d.sampleContinuous({rng.uniform(), rng.uniform()}, &pdf);
        int cu = std::min(nu - 1, int(p.x * nu)), cv = std::min(nv - 1, int(p.y * nv));
        ASSERT_GT(w[cv * nu + cu], 0.0f);
        ASSERT_NEAR(pdf, w[cv * nu + cu] / total * nu * nv, 1e-3f);
        ASSERT_NEAR(pdf, d.pdf(p), 1e-3f);
        ++counts[cv * nu + cu];
    }
    double chi2 = 0;
    for (size_t k = 0; k < w.size(); ++k) {
        if (w[k] == 0) continue;
        double e = n * w[k] / total;
        chi2 += (counts[k] - e) * (counts[k] - e) / e;
    }
    EXPECT_LT(chi2, 31.26);  // chi-square(9 dof) at p = 0.9995
}
