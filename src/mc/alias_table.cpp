#include "mc/alias_table.h"

#include <cmath>

namespace ps {

AliasTable::AliasTable(std::span<const float> weights) : slots_(weights.size()) {
    const size_t n = weights.size();
    if (n == 0) return;
    std::vector<double> w(n);
    double sum = 0;
    for (size_t i = 0; i < n; ++i) {
        w[i] = (std::isfinite(weights[i]) && weights[i] > 0) ? double(weights[i]) : 0.0;
        sum += w[i];
    }
    if (!(sum > 0)) {
        w.assign(n, 1.0);
        sum = double(n);
    }
    // Scaled so that the mean slot holds exactly 1; slots below 1 take an alias from one above.
    std::vector<double> scaled(n);
    std::vector<size_t> small, large;
    for (size_t i = 0; i < n; ++i) {
        slots_[i].pmf = float(w[i] / sum);
        scaled[i] = w[i] / sum * double(n);
        (scaled[i] < 1 ? small : large).push_back(i);
    }
    while (!small.empty() && !large.empty()) {
        size_t s = small.back(), l = large.back();
        small.pop_back();
        slots_[s].keep = float(scaled[s]);
        slots_[s].alias = int(l);
        scaled[l] -= 1 - scaled[s];
        if (scaled[l] < 1) {
            large.pop_back();
            small.push_back(l);
        }
    }
    // What remains is 1 up to rounding: those slots keep their outcome.
    for (size_t i : small) slots_[i] = {1, int(i), slots_[i].pmf};
    for (size_t i : large) slots_[i] = {1, int(i), slots_[i].pmf};
}

}  // namespace ps
