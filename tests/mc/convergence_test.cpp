// Convergence rates: the log-log slope of RMSE against N over independent runs.
// Plain Monte Carlo: -1/2. Jittered stratification of a smooth integrand in s dimensions:
// -(1/2 + 1/s). Scrambled Sobol (randomised QMC) on a smooth integrand: near -3/2 for small
// s, and clearly steeper than -1/2.
#include <gtest/gtest.h>

#include <cstdio>

#include "mc/convergence.h"
#include "mc/techniques.h"
#include "mc/test_integrands.h"

using namespace ps;

namespace {

double slopeOf(const char* technique, const char* integrand, int dims, std::vector<int> ns, int runs) {
    TestIntegrand t = makeTestIntegrand(integrand, dims);
    const Technique& tech = *findTechnique(technique);
    ConvergenceStudy s = studyConvergence([&](int n, Rng& rng) { return tech.run(t, n, rng); }, t.exact, ns, runs, 42);
    std::printf("[ slope    ] %-11s %-9s s=%d: %.3f\n", technique, integrand, dims, s.slope);
    return s.slope;
}

}  // namespace

TEST(Convergence, LogLogSlopeOfAPowerLawIsItsExponent) {
    std::vector<double> x{10, 100, 1000, 10000}, y;
    for (double v : x) y.push_back(3.0 * std::pow(v, -0.75));
    EXPECT_NEAR(logLogSlope(x, y), -0.75, 1e-12);
    EXPECT_TRUE(std::isnan(logLogSlope(std::vector<double>{1}, std::vector<double>{1})));
}

TEST(Convergence, IndependentSamplingConvergesAtMinusOneHalf) {
    for (int dims : {1, 4}) EXPECT_NEAR(slopeOf("independent", "exp", dims, {64, 256, 1024, 4096, 16384}, 64), -0.5, 0.1);
    EXPECT_NEAR(slopeOf("independent", "halfspace", 3, {64, 256, 1024, 4096, 16384}, 64), -0.5, 0.1);
}

TEST(Convergence, StratifiedSamplingConvergesAtMinusHalfMinusOneOverS) {
    // N = k^s exactly, so every grid is full.
    EXPECT_NEAR(slopeOf("stratified", "exp", 1, {16, 64, 256, 1024, 4096}, 64), -1.5, 0.12);
    EXPECT_NEAR(slopeOf("stratified", "exp", 2, {64, 256, 1024, 4096, 16384}, 64), -1.0, 0.1);
    EXPECT_NEAR(slopeOf("stratified", "exp", 3, {64, 512, 4096, 32768}, 48), -(0.5 + 1.0 / 3), 0.1);
    // A discontinuity crossing the cells: -(1/2 + 1/(2s)) (only boundary cells have variance).
    EXPECT_NEAR(slopeOf("stratified", "halfspace", 2, {64, 256, 1024, 4096, 16384}, 64), -0.75, 0.1);
}

TEST(Convergence, ScrambledSobolBeatsMinusOneHalfOnSmoothIntegrands) {
    EXPECT_LT(slopeOf("sobol", "exp", 2, {64, 256, 1024, 4096, 16384}, 32), -1.2);
    EXPECT_LT(slopeOf("sobol", "gaussian", 4, {64, 256, 1024, 4096, 16384}, 32), -0.9);
}
