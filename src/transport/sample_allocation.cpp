#include "transport/sample_allocation.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ps {

std::vector<int> proportionalAllocation(const std::vector<double>& weights, long long total, int minimum) {
    const size_t n = weights.size();
    std::vector<int> alloc(n, minimum);
    const long long rest = total - (long long)n * minimum;
    if (n == 0 || rest <= 0) return alloc;
    double sum = 0;
    for (double w : weights)
        if (std::isfinite(w) && w > 0) sum += w;
    auto weight = [&](size_t i) {
        if (!(sum > 0)) return 1.0 / double(n);
        return std::isfinite(weights[i]) && weights[i] > 0 ? weights[i] / sum : 0.0;
    };
    constexpr double kMaxPerPixel = 1 << 30;
    std::vector<double> frac(n);
    long long given = 0;
    for (size_t i = 0; i < n; ++i) {
        double x = std::min(kMaxPerPixel, double(rest) * weight(i));
        double f = std::floor(x);
        alloc[i] += int(f);
        given += (long long)f;
        frac[i] = x - f;
    }
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return frac[a] > frac[b]; });
    for (size_t k = 0; given < rest && k < n; ++k, ++given) ++alloc[order[k]];
    return alloc;
}

std::vector<size_t> largestK(const std::vector<double>& values, size_t k) {
    std::vector<size_t> idx(values.size());
    std::iota(idx.begin(), idx.end(), size_t(0));
    k = std::min(k, idx.size());
    auto before = [&](size_t a, size_t b) { return values[a] > values[b] || (values[a] == values[b] && a < b); };
    std::nth_element(idx.begin(), idx.begin() + std::ptrdiff_t(k), idx.end(), before);
    idx.resize(k);
    std::sort(idx.begin(), idx.end());
    return idx;
}

}  // namespace ps
