#include "mc/least_squares.h"

#include <cmath>

namespace ps {

std::optional<std::vector<double>> solveSpd(const std::vector<double>& a, const std::vector<double>& b, int n) {
    std::vector<double> l(size_t(n) * n, 0.0);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j <= i; ++j) {
            double sum = a[size_t(i) * n + j];
            for (int k = 0; k < j; ++k) sum -= l[size_t(i) * n + k] * l[size_t(j) * n + k];
            if (i == j) {
                // Relative pivot test: a pivot lost to cancellation means a singular system.
                if (!(sum > 1e-12 * std::abs(a[size_t(i) * n + i])) || sum <= 0) return std::nullopt;
                l[size_t(i) * n + i] = std::sqrt(sum);
            } else {
                l[size_t(i) * n + j] = sum / l[size_t(j) * n + j];
            }
        }
    }
    std::vector<double> y(static_cast<size_t>(n)), x(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        double sum = b[i];
        for (int k = 0; k < i; ++k) sum -= l[size_t(i) * n + k] * y[k];
        y[i] = sum / l[size_t(i) * n + i];
    }
    for (int i = n - 1; i >= 0; --i) {
        double sum = y[i];
        for (int k = i + 1; k < n; ++k) sum -= l[size_t(k) * n + i] * x[k];
        x[i] = sum / l[size_t(i) * n + i];
    }
    return x;
}

}  // namespace ps
