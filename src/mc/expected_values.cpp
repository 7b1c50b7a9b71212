#include "mc/expected_values.h"

namespace ps {

McEstimate estimateExpectedValues(const Integrand& partial, int dims, const PointSet& points) {
    Stopwatch clock;
    RunningStats s;
    clearUpperVectorState();
    for (int i = 0; i < points.n; ++i) s.add(partial(points.point(i).first(size_t(dims - 1))));
    return estimateFromStats(s, points.n, clock.seconds());
}

}  // namespace ps
