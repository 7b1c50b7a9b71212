#include "spectral/wavelengths.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace ps {

namespace {

// The density is A / cosh^2(b (lambda - c)); its antiderivative is (A/b) tanh(b (lambda - c)).
constexpr double kB = 0.0072, kC = 538;
const double kTanhLo = std::tanh(kB * (kLambdaMin - kC));
const double kTanhHi = std::tanh(kB * (kLambdaMax - kC));
const double kNorm = kB / (kTanhHi - kTanhLo);
// The same in float for sampleVisible (namespace scope: no initialisation guard per call).
const float tLo = float(kTanhLo), tRange = float(kTanhHi - kTanhLo), norm = float(kNorm);

}  // namespace

float visibleWavelengthPdf(float lambda) {
    if (!(lambda >= kLambdaMin && lambda <= kLambdaMax)) return 0;
    const double c = std::cosh(kB * (lambda - kC));
    return float(kNorm / (c * c));
}

float sampleVisibleWavelength(float u) {
    const double t = kTanhLo + double(u) * (kTanhHi - kTanhLo);
    const double lambda = kC + std::atanh(t) / kB;
    return float(std::fmin(std::fmax(lambda, kLambdaMin), kLambdaMax));
}

namespace {

// Natural logarithm of a positive normal float, branch-free so that the four wavelengths'
// run as one vector operation: x = m 2^e with m in [sqrt(1/2), sqrt(2)), and
// log m = 2 atanh(s), s = (m - 1) / (m + 1), |s| < 0.172, by its series to s^9 (truncation
// below 1e-9, so float rounding dominates).
inline float logPositive(float x) {
    int32_t bits;
    std::memcpy(&bits, &x, 4);
    // The exponent relative to sqrt(1/2) (bit pattern 0x3f3504f3), by an arithmetic shift.
    const int32_t e = (bits - 0x3f3504f3) >> 23;
    const int32_t mBits = bits - int32_t(uint32_t(e) << 23);
    float m;
    std::memcpy(&m, &mBits, 4);
    const float sRatio = (m - 1) / (m + 1), s2 = sRatio * sRatio;
    const float series = sRatio * (2 + s2 * (2.0f / 3 + s2 * (2.0f / 5 + s2 * (2.0f / 7 + s2 * (2.0f / 9)))));
    return float(e) * 0.69314718f + series;
}

}  // namespace

SampledWavelengths SampledWavelengths::sampleVisible(float u) {
    // Every camera sample draws these, so one logarithm per wavelength and nothing else:
    // the inverse CDF maps u to t = tanh(b (lambda - c)), so lambda = c + atanh(t) / b with
    // atanh(t) = log((1 + t) / (1 - t)) / 2, and the density A / cosh^2 is A (1 - t^2).
    SampledWavelengths w;
    w.u = u;
    for (int i = 0; i < kWavelengthSamples; ++i) {
        float up = u + float(i) / kWavelengthSamples;
        up = up > 1 ? up - 1 : up;
        const float t = tLo + up * tRange;
        const float lambda = float(kC) + logPositive((1 + t) / (1 - t)) * float(0.5 / kB);
        w.lambda[i] = lambda < kLambdaMin ? kLambdaMin : (lambda > kLambdaMax ? kLambdaMax : lambda);
        w.pdf[i] = norm * (1 - t * t);
    }
    return w;
}

SampledWavelengths SampledWavelengths::sampleUniform(float u, float lo, float hi) {
    SampledWavelengths w;
    w.lambda[0] = lo + u * (hi - lo);
    const float delta = (hi - lo) / kWavelengthSamples;
    for (int i = 1; i < kWavelengthSamples; ++i) {
        w.lambda[i] = w.lambda[i - 1] + delta;
        if (w.lambda[i] > hi) w.lambda[i] = lo + (w.lambda[i] - hi);
    }
    w.pdf.fill(1 / (hi - lo));
    return w;
}

void SampledWavelengths::terminateSecondary() {
    ++terminationRequests;
    if (secondaryTerminated()) return;
    for (int i = 1; i < kWavelengthSamples; ++i) pdf[i] = 0;
    pdf[0] /= kWavelengthSamples;
}

bool SampledWavelengths::secondaryTerminated() const {
    for (int i = 1; i < kWavelengthSamples; ++i)
        if (pdf[i] != 0) return false;
    return true;
}

}  // namespace ps
