// Least squares and the regression estimator on cases with exact answers.
#include <gtest/gtest.h>

#include "mc/least_squares.h"
#include "mc/regression.h"

using namespace ps;

TEST(LeastSquares, SolvesASpdSystemAndRejectsASingularOne) {
    std::vector<double> a{4, 2, 0, 2, 5, 1, 0, 1, 3}, b{2, 3, 4};
    auto x = solveSpd(a, b, 3);
    ASSERT_TRUE(x);
    for (int i = 0; i < 3; ++i) {
        double r = 0;
        for (int j = 0; j < 3; ++j) r += a[i * 3 + j] * (*x)[j];
        EXPECT_NEAR(r, b[i], 1e-12);
    }
    EXPECT_FALSE(solveSpd({1, 1, 1, 1}, {1, 2}, 2));
}

TEST(Regression, RecoversAnExactLinearModelWithZeroError) {
    // f lies in the span of the controls: the intercept is the integral exactly.
    Integrand f = [](std::span<const double> u) { return 3 + 2 * (u[0] - 0.5) - (u[1] - 0.5); };
    std::vector<ControlFunction> controls{{[](std::span<const double> u) { return u[0]; }, 0.5},
                                          {[](std::span<const double> u) { return u[1]; }, 0.5}};
    Rng rng(51);
    RegressionEstimate e = estimateRegression(f, controls, generatePoints(PointSetKind::Independent, 50, 2, rng));
    EXPECT_NEAR(e.estimate.value, 3.0, 1e-12);
    EXPECT_NEAR(e.estimate.standardError, 0.0, 1e-6);
    ASSERT_EQ(e.beta.size(), 2u);
    EXPECT_NEAR(e.beta[0], 2.0, 1e-10);
    EXPECT_NEAR(e.beta[1], -1.0, 1e-10);
    EXPECT_EQ(e.estimate.evaluations, 50);
}

TEST(Regression, FallsBackToThePlainMeanForDegenerateControls) {
    Integrand f = [](std::span<const double> u) { return u[0]; };
    std::vector<ControlFunction> constant{{[](std::span<const double>) { return 1.0; }, 1.0}};
    Rng rng(52);
    PointSet p = generatePoints(PointSetKind::Independent, 100, 1, rng);
    RegressionEstimate e = estimateRegression(f, constant, p);
    double mean = 0;
    for (double v : p.data) mean += v / p.n;
    EXPECT_NEAR(e.estimate.value, mean, 1e-12);
}
