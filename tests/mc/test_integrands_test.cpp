// The test integrands' exact integrals, partial integrals and importance densities, each
// checked against an independent Monte Carlo estimate (|difference| < 4 standard errors).
#include <gtest/gtest.h>

#include <cstdio>

#include "mc/expected_values.h"
#include "mc/importance_sampling.h"
#include "mc/plain_estimator.h"
#include "mc/test_integrands.h"
#include "mc_test_util.h"

using namespace ps;

TEST(TestIntegrands, ExactIntegralsAgreeWithMonteCarlo) {
    Rng rng(11);
    for (const std::string& name : testIntegrandNames()) {
        for (int dims : {1, 2, 3, 5, 10}) {
            TestIntegrand t = makeTestIntegrand(name, dims);
            PointSet p = generatePoints(PointSetKind::Independent, 200000, dims, rng);
            // The singular integrand has infinite variance: check it through its importance
            // density instead, whose weights have finite variance.
            McEstimate e = name == "singular" ? estimateImportance(t.f, *t.importance, p) : estimatePlain(t.f, p);
            EXPECT_NEAR(e.value, t.exact, 4 * e.standardError) << name << " s=" << dims;
            EXPECT_GT(e.standardError, 0) << name;
        }
    }
}

TEST(TestIntegrands, KnownClosedForms) {
    EXPECT_NEAR(makeTestIntegrand("halfspace", 1).exact, 0.4, 1e-14);
    EXPECT_NEAR(makeTestIntegrand("halfspace", 2).exact, 0.32, 1e-14);  // 0.8^2 / 2
    EXPECT_NEAR(makeTestIntegrand("ball", 2).exact, M_PI * 0.45 * 0.45, 1e-14);
    EXPECT_NEAR(makeTestIntegrand("ball", 3).exact, 4.0 / 3.0 * M_PI * std::pow(0.45, 3), 1e-14);
    EXPECT_NEAR(makeTestIntegrand("exp", 3).exact, std::pow(M_E - 1, 3), 1e-12);
    EXPECT_EQ(makeTestIntegrand("singular", 7).exact, 1.0);
    EXPECT_THROW(makeTestIntegrand("exp", 11), std::invalid_argument);
    EXPECT_THROW(makeTestIntegrand("nope", 2), std::invalid_argument);
}

TEST(TestIntegrands, PartialIntegralsIntegrateToTheExactValue) {
    Rng rng(12);
    for (const std::string& name : testIntegrandNames()) {
        for (int dims : {1, 2, 4}) {
            TestIntegrand t = makeTestIntegrand(name, dims);
            ASSERT_TRUE(t.partial) << name;
            PointSet p = generatePoints(PointSetKind::Independent, 100000, std::max(1, dims - 1), rng);
            McEstimate e = estimateExpectedValues(t.partial, dims, p);
            if (dims == 1) {
                EXPECT_NEAR(e.value, t.exact, 1e-12) << name;  // nothing left to sample
                continue;
            }
            // singular's partial keeps the singularity in the other coordinates (infinite
            // variance, so its standard error means little): a fixed tolerance of about 5 times
            // the typical error sqrt(ln n / n).
            double tol = name == "singular" ? 0.05 : 4 * e.standardError;
            EXPECT_NEAR(e.value, t.exact, tol) << name << " s=" << dims;
        }
    }
}

TEST(TestIntegrands, ImportanceDensitiesAreNormalisedAndSampledByTheirPdf) {
    Rng rng(13);
    for (const std::string& name : testIntegrandNames()) {
        TestIntegrand t = makeTestIntegrand(name, 1);
        if (!t.importance) continue;
        // Normalised: the mean of pdf over uniform points is its integral.
        PointSet u = generatePoints(PointSetKind::Independent, 200000, 1, rng);
        Integrand pdf = t.importance->pdf;
        McEstimate integral = estimatePlain(pdf, u);
        EXPECT_NEAR(integral.value, 1.0, std::max(4 * integral.standardError, 1e-3)) << name;
        // Sampled by it: the histogram of mapped points against pdf integrated per bin (chi-square).
        const int bins = 20, n = 100000;
        std::vector<int> hist(bins, 0);
        std::vector<double> x(1);
        for (int i = 0; i < n; ++i) {
            double v = u.data[size_t(i)];
            t.importance->sample(std::span<const double>(&v, 1), x);
            ++hist[std::min(bins - 1, int(x[0] * bins))];
        }
        double chi2 = 0;
        for (int b = 0; b < bins; ++b) {
            // Expected mass by a fine midpoint rule on the bin.
            double mass = 0;
            for (int j = 0; j < 200; ++j) {
                double xv = (b + (j + 0.5) / 200) / bins;
                mass += pdf(std::span<const double>(&xv, 1)) / (200.0 * bins);
            }
            double expected = n * mass;
            chi2 += (hist[b] - expected) * (hist[b] - expected) / expected;
        }
        std::printf("[ density  ] %-10s integral %.4f, chi2 %.1f (19 dof)\n", name.c_str(), integral.value, chi2);
        EXPECT_LT(chi2, 50.0) << name;  // p < 1e-4 for 19 degrees of freedom
    }
}
