#include "mc/antithetic.h"

#include <vector>

namespace ps {

McEstimate estimateAntithetic(const Integrand& f, const PointSet& points) {
    Stopwatch clock;
    RunningStats s;
    std::vector<double> mirror(static_cast<size_t>(points.dims));
    clearUpperVectorState();
    for (int i = 0; i < points.n; ++i) {
        std::span<const double> u = points.point(i);
        for (int d = 0; d < points.dims; ++d) mirror[d] = 1.0 - u[d];
        s.add(0.5 * (f(u) + f(mirror)));
    }
    return estimateFromStats(s, 2 * int64_t(points.n), clock.seconds());
}

}  // namespace ps
