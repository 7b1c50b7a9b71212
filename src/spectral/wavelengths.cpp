#include "spectral/wavelengths.h"

#include <cmath>

namespace ps {

namespace {

// The density is A / cosh^2(b (lambda - c)); its antiderivative is (A/b) tanh(b (lambda - c)).
constexpr double kB = 0.0072, kC = 538;
const double kTanhLo = std::tanh(kB * (kLambdaMin - kC));
const double kTanhHi = std::tanh(kB * (kLambdaMax - kC));
const double kNorm = kB / (kTanhHi - kTanhLo);

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

SampledWavelengths SampledWavelengths::sampleVisible(float u) {
    SampledWavelengths w;
    for (int i = 0; i < kWavelengthSamples; ++i) {
        float up = u + float(i) / kWavelengthSamples;
        if (up > 1) up -= 1;
        w.lambda[i] = sampleVisibleWavelength(up);
        w.pdf[i] = visibleWavelengthPdf(w.lambda[i]);
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
