#include "mc/plain_estimator.h"

namespace ps {

McEstimate estimatePlain(const Integrand& f, const PointSet& points) {
    Stopwatch clock;
    RunningStats s;
    clearUpperVectorState();
    for (int i = 0; i < points.n; ++i) s.add(f(points.point(i)));
    return estimateFromStats(s, points.n, clock.seconds());
}

}  // namespace ps
