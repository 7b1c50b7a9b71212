#include "transport/scrambled_sets.h"

#include <algorithm>

#include "util/memory_limit.h"

namespace ps {

int batchCount(int spp) {
    const int k = std::min(8, spp / 4);
    return k >= 2 ? k : 1;
}

int scramblingCount(const std::string& sampler, int spp) { return sampler == "independent" ? 1 : batchCount(spp); }

std::vector<int> scramblingStarts(int spp, int sets) {
    std::vector<int> starts;
    for (int b = 1; b < sets; ++b) starts.push_back(int((long long)spp * b / sets));
    return starts;
}

ScrambledPixelVariance::ScrambledPixelVariance(size_t pixels, int sets) : pixels_(pixels), sets_(sets) {
    requireMemory("--stats' " + std::to_string(sets) + " scrambled sets of " + std::to_string(pixels) + " pixels",
                  double(pixels) * sets * (sizeof(double) + sizeof(int)));
    sum_.assign(pixels * size_t(sets), 0.0);
    count_.assign(pixels * size_t(sets), 0);
}

Film::ErrorEstimate ScrambledPixelVariance::errorEstimate() const {
    Film::ErrorEstimate e;
    if (pixels_ == 0) return e;
    for (size_t p = 0; p < pixels_; ++p) {
        double total = 0;
        long long n = 0;
        int filled = 0;
        for (int b = 0; b < sets_; ++b) {
            total += sum_[size_t(b) * pixels_ + p];
            n += count_[size_t(b) * pixels_ + p];
            filled += count_[size_t(b) * pixels_ + p] > 0;
        }
        if (filled < 2) continue;
        const double mean = total / double(n);
        // Var(mean) = sum_b n_b (m_b - m)^2 / ((K - 1) n), the set means weighted by their counts.
        double ss = 0;
        for (int b = 0; b < sets_; ++b) {
            const int c = count_[size_t(b) * pixels_ + p];
            if (c == 0) continue;
            const double d = sum_[size_t(b) * pixels_ + p] / c - mean;
            ss += c * d * d;
        }
        const double v = ss / (double(filled - 1) * double(n));
        e.meanVariance += v;
        e.meanRelativeVariance += v / (mean * mean + Film::kRelativeEpsilon);
    }
    e.meanVariance /= double(pixels_);
    e.meanRelativeVariance /= double(pixels_);
    return e;
}

}  // namespace ps
