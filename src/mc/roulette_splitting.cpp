#include "mc/roulette_splitting.h"

#include <algorithm>
#include <vector>

namespace ps {

McEstimate estimateRoulette(const Integrand& f, int dims, double q, const PointSet& points) {
    Stopwatch clock;
    RunningStats s;
    int64_t evaluations = 0;
    clearUpperVectorState();
    for (int i = 0; i < points.n; ++i) {
        std::span<const double> u = points.point(i);
        if (u[size_t(dims)] < q) {
            ++evaluations;
            s.add(f(u.first(size_t(dims))) / q);
        } else {
            s.add(0.0);
        }
    }
    return estimateFromStats(s, evaluations, clock.seconds());
}

int splittingPointDims(int dims, int prefix, int k) { return prefix + k * (dims - prefix); }

McEstimate estimateSplitting(const Integrand& f, int dims, int prefix, int k, const PointSet& points) {
    Stopwatch clock;
    RunningStats s;
    std::vector<double> x(static_cast<size_t>(dims));
    const int suffix = dims - prefix;
    clearUpperVectorState();
    for (int i = 0; i < points.n; ++i) {
        std::span<const double> u = points.point(i);
        std::copy_n(u.begin(), prefix, x.begin());
        double sum = 0;
        for (int c = 0; c < k; ++c) {
            std::copy_n(u.begin() + prefix + c * suffix, suffix, x.begin() + prefix);
            sum += f(x);
        }
        s.add(sum / k);
    }
    return estimateFromStats(s, int64_t(points.n) * k, clock.seconds());
}

}  // namespace ps
