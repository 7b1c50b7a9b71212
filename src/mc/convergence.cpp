#include "mc/convergence.h"

#include <cmath>
#include <limits>

namespace ps {

double logLogSlope(std::span<const double> x, std::span<const double> y) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int m = 0;
    for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
        if (!(x[i] > 0) || !(y[i] > 0)) continue;
        double lx = std::log(x[i]), ly = std::log(y[i]);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++m;
    }
    double denom = m * sxx - sx * sx;
    if (m < 2 || !(denom > 0)) return std::numeric_limits<double>::quiet_NaN();
    return (m * sxy - sx * sy) / denom;
}

ConvergenceStudy studyConvergence(const EstimatorRun& run, double exact, std::span<const int> ns, int runs,
                                  uint64_t seed) {
    ConvergenceStudy study;
    std::vector<double> xs, ys;
    for (int n : ns) {
        RunningStats estimates;
        double sq = 0, seconds = 0, evaluations = 0, reported = 0;
        for (int r = 0; r < runs; ++r) {
            Rng rng(hashCombine(seed, uint64_t(n)), mix64(uint64_t(r) + 1));
            McEstimate e = run(n, rng);
            estimates.add(e.value);
            sq += (e.value - exact) * (e.value - exact);
            seconds += e.seconds;
            evaluations += double(e.evaluations);
            reported += e.standardError;
        }
        ConvergencePoint p;
        p.n = n;
        p.evaluations = evaluations / runs;
        p.mean = estimates.mean();
        p.standardError = std::sqrt(estimates.variance());
        p.reportedError = reported / runs;
        p.rmse = std::sqrt(sq / runs);
        p.seconds = seconds / runs;
        p.efficiency = efficiency(estimates.variance(), p.seconds);
        study.points.push_back(p);
        xs.push_back(p.evaluations);
        ys.push_back(p.rmse);
    }
    study.slope = logLogSlope(xs, ys);
    return study;
}

}  // namespace ps
