#include "spectral/piecewise_linear.h"
#include "spectral/cie.h"
#include "spectral/wavelengths.h"

#include <algorithm>

namespace ps {

float PiecewiseLinearTable::at(float l) const {
    if (lambda.empty() || !(l >= lambda.front() && l <= lambda.back())) return 0;
    // The last sample at or below l, kept below the final one so that [i, i+1] exists.
    size_t i = size_t(std::upper_bound(lambda.begin(), lambda.end(), l) - lambda.begin());
    i = std::min(i == 0 ? 0 : i - 1, lambda.size() >= 2 ? lambda.size() - 2 : 0);
    if (lambda.size() == 1) return value[0];
    const float t = (l - lambda[i]) / (lambda[i + 1] - lambda[i]);
    return (1 - t) * value[i] + t * value[i + 1];
}

float PiecewiseLinearTable::maxValue() const {
    return value.empty() ? 0.0f : *std::max_element(value.begin(), value.end());
}

PiecewiseLinearTable PiecewiseLinearTable::fromInterleaved(std::span<const float> pairs, bool normalize) {
    PiecewiseLinearTable t;
    const size_t n = pairs.size() / 2;
    if (n == 0) return t;
    if (pairs[0] > kLambdaMin) {
        t.lambda.push_back(kLambdaMin - 1);
        t.value.push_back(pairs[1]);
    }
    for (size_t i = 0; i < n; ++i) {
        t.lambda.push_back(pairs[2 * i]);
        t.value.push_back(pairs[2 * i + 1]);
    }
    if (t.lambda.back() < kLambdaMax) {
        t.lambda.push_back(kLambdaMax + 1);
        t.value.push_back(t.value.back());
    }
    if (normalize) {
        double y = 0;
        for (int i = 0; i < kCieSamples; ++i) y += double(t.at(float(kCieLambdaMin + i))) * kCieY[i];
        if (y > 0)
            for (float& v : t.value) v = float(v * (kCieYIntegral / y));
    }
    return t;
}

}  // namespace ps
