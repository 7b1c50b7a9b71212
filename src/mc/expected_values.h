// The use of expected values (thesis ch. 2, "Variance reduction I: analytic integration"):
// when the integral of f over its last coordinate is known in closed form, integrate it out
// and estimate only the remaining s-1 dimensions. By the law of total variance this never
// increases variance: Var E[f|u'] = Var f - E Var[f|u'].
#pragma once
#include "mc/mc_estimate.h"
#include "mc/point_sets.h"

namespace ps {

// partial(u') = integral of f(u', x) over x in [0,1), for u' in [0,1)^(s-1). points holds at
// least s-1 coordinates per point; only the first `dims - 1` are passed (none when s = 1).
McEstimate estimateExpectedValues(const Integrand& partial, int dims, const PointSet& points);

}  // namespace ps
