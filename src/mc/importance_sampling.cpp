#include "mc/importance_sampling.h"

#include <vector>

namespace ps {

McEstimate estimateImportance(const Integrand& f, const ImportanceDensity& density, const PointSet& points) {
    Stopwatch clock;
    RunningStats s;
    std::vector<double> x(static_cast<size_t>(points.dims));
    clearUpperVectorState();
    for (int i = 0; i < points.n; ++i) {
        density.sample(points.point(i), x);
        double p = density.pdf(x);
        // f/p is 0 where p is 0 only if f is too; the caller's density must cover f's support.
        s.add(p > 0 ? f(x) / p : 0.0);
    }
    return estimateFromStats(s, points.n, clock.seconds());
}

}  // namespace ps
