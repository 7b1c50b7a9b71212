// The basic Monte Carlo estimator (thesis §2.3): the mean of f over a point set. With
// independent points this is plain Monte Carlo; with stratified, Latin hypercube or
// scrambled Sobol points (point_sets.h) it is the uniform-sample-placement family.
#pragma once
#include "mc/mc_estimate.h"
#include "mc/point_sets.h"

namespace ps {

McEstimate estimatePlain(const Integrand& f, const PointSet& points);

}  // namespace ps
