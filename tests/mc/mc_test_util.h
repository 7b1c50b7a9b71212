// Shared helpers of the Monte Carlo toolbox tests: repeated independent runs of an estimator.
#pragma once
#include <cmath>
#include <functional>

#include "mc/estimator.h"
#include "mc/mc_estimate.h"
#include "mc/rng.h"

namespace ps::test {

// Statistics of `runs` independent estimates, run r seeded by (seed, r).
struct RunsSummary {
    RunningStats estimates;   // of the runs' values: mean, spread of one run
    double meanEvaluations = 0;
    double meanReportedVariance = 0;  // mean of the runs' own standardError^2
};

inline RunsSummary repeatRuns(const std::function<McEstimate(Rng&)>& run, int runs, uint64_t seed) {
    RunsSummary s;
    for (int r = 0; r < runs; ++r) {
        Rng rng(hashCombine(seed, uint64_t(r)), mix64(seed + uint64_t(r)));
        McEstimate e = run(rng);
        s.estimates.add(e.value);
        s.meanEvaluations += double(e.evaluations) / runs;
        s.meanReportedVariance += e.standardError * e.standardError / runs;
    }
    return s;
}

// |mean - exact| in units of the mean's standard error.
inline double sigmasFrom(const RunningStats& s, double exact) {
    double se = s.standardError();
    double diff = std::abs(s.mean() - exact);
    if (se > 0) return diff / se;
    return diff <= 1e-12 * std::max(1.0, std::abs(exact)) ? 0.0 : INFINITY;  // zero-variance estimators
}

}  // namespace ps::test
