// Russian roulette and splitting (thesis ch. 2, "Russian roulette and splitting") as
// transforms of the basic estimator. Both keep the mean and trade variance against cost:
// - roulette evaluates f only with probability q and weights the survivors by 1/q:
//   E = I, Var = E[f^2]/q - I^2, expected cost q evaluations per sample;
// - splitting shares the first `prefix` coordinates and averages k independent draws of the
//   rest: Var = Var(E[f|prefix]) + E[Var(f|prefix)]/k, cost k evaluations per sample.
#pragma once
#include "mc/mc_estimate.h"
#include "mc/point_sets.h"

namespace ps {

// points has dims + 1 coordinates: the last one decides survival (survive if < q).
McEstimate estimateRoulette(const Integrand& f, int dims, double q, const PointSet& points);

// Coordinates per point needed for splitting an s-dimensional f after `prefix` coordinates
// into k copies: prefix + k (s - prefix). Copy c of the suffix is at prefix + c (s - prefix).
int splittingPointDims(int dims, int prefix, int k);
McEstimate estimateSplitting(const Integrand& f, int dims, int prefix, int k, const PointSet& points);

}  // namespace ps
