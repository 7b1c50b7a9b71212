// Control variates (thesis ch. 2, "Control variates"): estimate the integral of f - beta g
// and add back beta G, where G is g's known integral. The variance is
// Var f - 2 beta Cov(f,g) + beta^2 Var g, smallest at beta* = Cov(f,g)/Var g, where it is
// (1 - rho^2) Var f. beta = 1 is the thesis's difference form; it can increase the variance
// when g is a poor match, which the estimated beta* never does (asymptotically).
#pragma once
#include "mc/regression.h"

namespace ps {

// Fixed coefficient: unbiased for any beta.
McEstimate estimateControlVariate(const Integrand& f, const ControlFunction& control, double beta,
                                  const PointSet& points);

// beta* estimated from the same samples: the one-control case of estimateRegression.
RegressionEstimate estimateControlVariateOptimal(const Integrand& f, const ControlFunction& control,
                                                 const PointSet& points);

}  // namespace ps
