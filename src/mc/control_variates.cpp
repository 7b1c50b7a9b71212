#include "mc/control_variates.h"

namespace ps {

McEstimate estimateControlVariate(const Integrand& f, const ControlFunction& control, double beta,
                                  const PointSet& points) {
    Stopwatch clock;
    RunningStats s;
    clearUpperVectorState();
    for (int i = 0; i < points.n; ++i) {
        std::span<const double> u = points.point(i);
        s.add(f(u) - beta * (control.g(u) - control.integral));
    }
    return estimateFromStats(s, points.n, clock.seconds());
}

RegressionEstimate estimateControlVariateOptimal(const Integrand& f, const ControlFunction& control,
                                                 const PointSet& points) {
    return estimateRegression(f, {control}, points);
}

}  // namespace ps
