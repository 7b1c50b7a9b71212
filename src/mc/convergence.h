// Measuring an estimator's convergence (thesis ch. 2: error, efficiency): run it R times
// independently at each of several sample counts N, take the RMSE against the exact value,
// and fit the rate as the least-squares slope of log RMSE against log N (-1/2 for plain
// Monte Carlo; steeper for stratified and quasi-Monte Carlo on smooth integrands).
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "mc/mc_estimate.h"
#include "mc/rng.h"

namespace ps {

// Least-squares slope of log y against log x (points with x or y <= 0 are skipped; NaN if
// fewer than two remain).
double logLogSlope(std::span<const double> x, std::span<const double> y);

struct ConvergencePoint {
    int n = 0;                  // requested sample count
    double evaluations = 0;     // mean integrand evaluations per run (the cost)
    double mean = 0;            // mean estimate over the runs
    double standardError = 0;   // observed standard deviation of one run's estimate
    double reportedError = 0;   // mean of the runs' own standard-error estimates
    double rmse = 0;            // against the exact value
    double seconds = 0;         // mean seconds per run
    double efficiency = 0;      // 1 / (variance * seconds), variance = standardError^2
};

struct ConvergenceStudy {
    std::vector<ConvergencePoint> points;
    double slope = 0;  // of RMSE against evaluations
};

using EstimatorRun = std::function<McEstimate(int n, Rng& rng)>;

// Run r at sample count n uses its own stream keyed by (seed, n, r), so results do not
// depend on which counts are studied or in what order.
ConvergenceStudy studyConvergence(const EstimatorRun& run, double exact, std::span<const int> ns, int runs,
                                  uint64_t seed);

}  // namespace ps
