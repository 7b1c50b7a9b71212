#include "mc/autocorrelation.h"

#include <vector>

namespace ps {

AutocorrelationSummary integratedAutocorrelation(std::span<const double> x) {
    const size_t n = x.size();
    AutocorrelationSummary out;
    out.ess = double(n);
    if (n < 4) return out;
    double mean = 0;
    for (double v : x) mean += v;
    mean /= double(n);
    // Autocovariance with the 1/N normalisation (the positive-definite estimate Geyer uses).
    auto gamma = [&](size_t k) {
        double s = 0;
        for (size_t i = 0; i + k < n; ++i) s += (x[i] - mean) * (x[i + k] - mean);
        return s / double(n);
    };
    double g0 = gamma(0);
    if (!(g0 > 0)) return out;
    double sum = 0;  // sum of Gamma_m, m >= 0
    size_t lag = 0;
    for (; 2 * lag + 1 < n; ++lag) {
        double pair = (lag == 0 ? g0 : gamma(2 * lag)) + gamma(2 * lag + 1);
        if (pair <= 0) break;
        sum += pair;
    }
    // tau = (-gamma_0 + 2 sum_m Gamma_m) / gamma_0.
    out.tau = (2 * sum - g0) / g0;
    if (out.tau <= 0) out.tau = 1.0 / double(n);
    out.ess = double(n) / out.tau;
    out.lags = int(2 * lag + 1);
    return out;
}

}  // namespace ps
