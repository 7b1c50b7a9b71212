#include "mc/regression.h"

#include <cmath>

#include "mc/least_squares.h"

namespace ps {

RegressionEstimate estimateRegression(const Integrand& f, const std::vector<ControlFunction>& controls,
                                      const PointSet& points) {
    Stopwatch clock;
    const int p = int(controls.size()) + 1, n = points.n;
    // Design matrix rows [1, g_1 - G_1, ...]; accumulate X^T X and X^T y in one pass.
    std::vector<double> rows(size_t(n) * p), y(static_cast<size_t>(n)), xtx(size_t(p) * p, 0.0), xty(size_t(p), 0.0);
    RunningStats plain;
    clearUpperVectorState();
    for (int i = 0; i < n; ++i) {
        std::span<const double> u = points.point(i);
        double* r = &rows[size_t(i) * p];
        r[0] = 1;
        for (int j = 1; j < p; ++j) r[j] = controls[j - 1].g(u) - controls[j - 1].integral;
        y[i] = f(u);
        plain.add(y[i]);
        for (int a = 0; a < p; ++a) {
            xty[a] += r[a] * y[i];
            for (int b = 0; b < p; ++b) xtx[size_t(a) * p + b] += r[a] * r[b];
        }
    }
    RegressionEstimate out;
    auto theta = n > p ? solveSpd(xtx, xty, p) : std::nullopt;
    std::vector<double> e0(size_t(p), 0.0);
    e0[0] = 1;
    auto inv0 = theta ? solveSpd(xtx, e0, p) : std::nullopt;
    if (!theta || !inv0) {
        out.estimate = estimateFromStats(plain, n, clock.seconds());
        out.beta.assign(controls.size(), 0.0);
        return out;
    }
    double rss = 0;
    for (int i = 0; i < n; ++i) {
        double fit = 0;
        for (int j = 0; j < p; ++j) fit += rows[size_t(i) * p + j] * (*theta)[j];
        rss += (y[i] - fit) * (y[i] - fit);
    }
    double s2 = rss / double(n - p);
    out.estimate = {(*theta)[0], std::sqrt(std::max(0.0, s2 * (*inv0)[0])), n, clock.seconds()};
    out.beta.assign(theta->begin() + 1, theta->end());
    return out;
}

}  // namespace ps
