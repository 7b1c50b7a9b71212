// Importance sampling (thesis ch. 2, "Importance sampling"): draw X with density p and
// average f(X)/p(X). Variance vanishes when p is proportional to f (for f >= 0); a p with
// heavier tails than f can turn an infinite-variance integrand into a finite one.
#pragma once
#include "mc/mc_estimate.h"
#include "mc/point_sets.h"

namespace ps {

struct ImportanceDensity {
    // Density on [0,1)^s with respect to Lebesgue measure.
    std::function<double(std::span<const double>)> pdf;
    // Maps a uniform point u in [0,1)^s to x with density pdf (e.g. by inversion, §2.4.1).
    std::function<void(std::span<const double> u, std::span<double> x)> sample;
};

// The uniform points are mapped through density.sample, so stratified or Sobol points
// compose with importance sampling.
McEstimate estimateImportance(const Integrand& f, const ImportanceDensity& density, const PointSet& points);

}  // namespace ps
