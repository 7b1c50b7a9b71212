// Each variance-reduction technique does what the thesis says on the case it is meant for,
// and antithetic variates fail where they must. Variances are per evaluation (variance of
// the estimate times its evaluations), the fair comparison at equal cost.
#include <gtest/gtest.h>

#include <cstdio>

#include "mc/antithetic.h"
#include "mc/control_variates.h"
#include "mc/techniques.h"
#include "mc/test_integrands.h"
#include "mc_test_util.h"

using namespace ps;
using namespace ps::test;

namespace {

// Variance of one run times its evaluations, measured over independent runs.
double variancePerEvaluation(const TestIntegrand& t, const std::string& technique, int n, uint64_t seed) {
    const Technique& tech = *findTechnique(technique);
    RunsSummary s = repeatRuns([&](Rng& rng) { return tech.run(t, n, rng); }, 300, seed);
    return s.estimates.variance() * s.meanEvaluations;
}

}  // namespace

TEST(VarianceReduction, TechniquesBeatPlainMonteCarloOnTheirCases) {
    struct Case {
        const char* integrand;
        int dims;
        const char* technique;
        double maxRatio;  // variance per evaluation relative to independent sampling
    };
    // Expected ratios (1 - rho^2 for the controls; analytic for the rest) are well below
    // these bounds; a 300-run variance is known to about +-16% (2 sigma).
    const Case cases[] = {
        {"exp", 1, "antithetic", 0.1},    // monotone: Cov(f(u), f(1-u)) is strongly negative
        {"exp", 3, "antithetic", 0.5},
        {"exp", 2, "control", 0.3},       // e^u is nearly linear
        {"exp", 3, "regression", 0.2},
        {"exp", 3, "importance", 0.2},    // p ~ 1 + u follows e^u
        {"gaussian", 2, "importance", 0.1},
        {"gaussian", 2, "expected", 0.7}, // one of two factors integrated exactly
        {"ball", 2, "expected", 0.5},
        {"exp", 2, "stratified", 0.01},
        {"exp", 2, "sobol", 0.001},
    };
    for (const Case& c : cases) {
        TestIntegrand t = makeTestIntegrand(c.integrand, c.dims);
        double plain = variancePerEvaluation(t, "independent", 1024, 1);
        double v = variancePerEvaluation(t, c.technique, 1024, 2);
        std::printf("[ variance ] %-9s s=%d %-11s / independent = %.4g\n", c.integrand, c.dims, c.technique, v / plain);
        EXPECT_LT(v / plain, c.maxRatio) << c.technique << " on " << c.integrand;
    }
}

TEST(VarianceReduction, AntitheticVariatesDoNotHelpASymmetricIntegrand) {
    // gaussian is symmetric about 1/2 in every coordinate, so f(1-u) = f(u): a pair is worth
    // one sample at twice the cost, and the variance per evaluation doubles exactly.
    TestIntegrand t = makeTestIntegrand("gaussian", 2);
    double plain = variancePerEvaluation(t, "independent", 1024, 3);
    double anti = variancePerEvaluation(t, "antithetic", 1024, 4);
    std::printf("[ variance ] gaussian  s=2 antithetic  / independent = %.4g (2 expected)\n", anti / plain);
    EXPECT_GT(anti / plain, 1.5);
    EXPECT_LT(anti / plain, 2.7);
    // (u - 1/2)^2: the same on a non-monotone polynomial, checked through the estimator itself.
    Integrand f = [](std::span<const double> u) { return (u[0] - 0.5) * (u[0] - 0.5); };
    Rng rng(9);
    McEstimate e = estimateAntithetic(f, generatePoints(PointSetKind::Independent, 4096, 1, rng));
    double varPerEval = e.standardError * e.standardError * double(e.evaluations);
    // Var f = 1/80 - 1/144 = 1/180: antithetic gives 2/180 per evaluation.
    EXPECT_NEAR(varPerEval, 2.0 / 180, 0.15 * 2.0 / 180);
}

TEST(VarianceReduction, OptimalControlCoefficientIsEstimatedAndFixedBetaCanHurt) {
    // f = e^u with control g = u: Cov(e^u, u) = 1 - (e - 1)/2 = (3 - e)/2, so
    // beta* = Cov / Var u = 6 (3 - e).
    Integrand f = [](std::span<const double> u) { return std::exp(u[0]); };
    ControlFunction g{[](std::span<const double> u) { return u[0]; }, 0.5};
    Rng rng(10);
    PointSet p = generatePoints(PointSetKind::Independent, 100000, 1, rng);
    RegressionEstimate opt = estimateControlVariateOptimal(f, g, p);
    ASSERT_EQ(opt.beta.size(), 1u);
    EXPECT_NEAR(opt.beta[0], 6 * (3 - M_E), 0.02);
    // Var f = (e^2 - 1)/2 - (e - 1)^2; optimal residual variance Var f - beta*^2 / 12.
    double varF = (M_E * M_E - 1) / 2 - (M_E - 1) * (M_E - 1);
    double bstar = 6 * (3 - M_E), varOpt = varF - bstar * bstar / 12;
    EXPECT_NEAR(opt.estimate.standardError * opt.estimate.standardError * p.n, varOpt, 0.05 * varOpt);
    // A badly chosen fixed beta = -1 adds variance: Var f + 2 Cov + Var g > Var f (Cov = beta*/12).
    McEstimate bad = estimateControlVariate(f, g, -1.0, p);
    double varBad = varF + 2 * bstar / 12 + 1.0 / 12;
    EXPECT_NEAR(bad.standardError * bad.standardError * p.n, varBad, 0.05 * varBad);
    EXPECT_GT(varBad, varF);
}
