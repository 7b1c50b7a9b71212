// Regression methods (thesis ch. 2, "Correlated estimators: regression methods"): fit
// f(u) ~ alpha + sum_j beta_j (g_j(u) - G_j) by least squares over the samples, where the
// controls g_j have known integrals G_j. Because every centred control integrates to zero,
// the fitted intercept alpha estimates the integral of f. The coefficients are estimated from
// the same samples, which makes the estimator biased by O(1/n) (negligible next to its
// O(1/sqrt n) error) and lets it find the best linear combination automatically.
#pragma once
#include <vector>

#include "mc/mc_estimate.h"
#include "mc/point_sets.h"

namespace ps {

struct ControlFunction {
    Integrand g;
    double integral = 0;  // exact integral of g over [0,1)^s
};

struct RegressionEstimate {
    McEstimate estimate;
    std::vector<double> beta;  // fitted coefficient per control
};

// Needs points.n > controls.size() + 1. The standard error is the OLS standard error of the
// intercept, s^2 [(X^T X)^{-1}]_00. Evaluations count f only (controls are assumed cheap).
// Falls back to the plain mean if the controls are degenerate over the samples.
RegressionEstimate estimateRegression(const Integrand& f, const std::vector<ControlFunction>& controls,
                                      const PointSet& points);

}  // namespace ps
