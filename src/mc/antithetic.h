// Antithetic variates (thesis ch. 2, "Correlated estimators"): average f(u) and f(1-u). The
// pair's variance is (Var f + Cov(f(u), f(1-u)))/2, so it helps when f is monotone in each
// coordinate (negative covariance) and costs double for an f symmetric about 1/2, where
// f(1-u) = f(u) and the pair is no better than a single sample.
#pragma once
#include "mc/mc_estimate.h"
#include "mc/point_sets.h"

namespace ps {

// One pair per point: 2 * points.n evaluations; the standard error is over pairs.
McEstimate estimateAntithetic(const Integrand& f, const PointSet& points);

}  // namespace ps
