// Shared helpers of the spectral tests: exact sums over the 1 nm grid and Monte Carlo
// estimates through the sensor.
#pragma once
#include <array>
#include <cmath>
#include <functional>
#include <random>

#include "spectral/cie.h"
#include "spectral/colorimetry.h"
#include "spectral/sensor.h"
#include "spectral/spectrum_source.h"

namespace ps::test {

// RGB of a reflectance under `space`'s illuminant, relative to a perfect white: sum over the
// 1 nm grid of cmf * s * illuminant / sum of ybar * illuminant, in the space's RGB.
inline std::array<double, 3> reflectanceRGB(const SpectrumSource& s, const RGBColorSpace& space) {
    const Colorimetry& c = colorimetry(space);
    XYZ xyz{0, 0, 0};
    double y = 0;
    for (int i = 0; i < kCieSamples; ++i) {
        const double e = c.illuminant.value[size_t(i)];
        const double v = s.at(float(kCieLambdaMin + i)) * e;
        xyz[0] += kCieX[i] * v;
        xyz[1] += kCieY[i] * v;
        xyz[2] += kCieZ[i] * v;
        y += kCieY[i] * e;
    }
    for (double& v : xyz) v /= y;
    return c.rgbFromXYZ * xyz;
}

// What the film's sensor outputs, in expectation over the wavelengths, for radiance L(lambda)
// (lambda in nm): outputFromSensor * imagingRatio * the integral of (xbar, ybar, zbar) L, summed
// over the 1 nm grid. The sensor looks the matching functions up at the nearest whole nm, so the
// sum differs from its expectation only by L's curvature within each nm.
inline std::array<double, 3> sensorRGB(const Sensor& sensor, const std::function<double(double)>& L) {
    std::array<double, 3> xyz{0, 0, 0};
    for (int i = 0; i < kCieSamples; ++i) {
        const double v = L(kCieLambdaMin + i);
        xyz[0] += kCieX[i] * v;
        xyz[1] += kCieY[i] * v;
        xyz[2] += kCieZ[i] * v;
    }
    for (double& v : xyz) v *= sensor.imagingRatio();
    return sensor.outputFromSensor() * xyz;
}

struct Estimate {
    std::array<double, 3> mean, stderr_;
};

// Mean and standard error of the sensor's output RGB for emitted radiance s * scale, over n
// independent wavelength samples.
inline Estimate sensorEstimate(const Sensor& sensor, const SpectrumSource& s, double scale, int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u01(0, 1);
    std::array<double, 3> sum{0, 0, 0}, sum2{0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const SampledWavelengths w = SampledWavelengths::sampleVisible(u01(rng));
        SpectralValues L = s.sample(w);
        for (float& v : L) v = float(v * scale);
        const auto rgb = sensor.toOutputRGB(L, w);
        for (int c = 0; c < 3; ++c) {
            sum[c] += rgb[c];
            sum2[c] += rgb[c] * rgb[c];
        }
    }
    Estimate e;
    for (int c = 0; c < 3; ++c) {
        e.mean[c] = sum[c] / n;
        e.stderr_[c] = std::sqrt(std::max(0.0, sum2[c] / n - e.mean[c] * e.mean[c]) / n);
    }
    return e;
}

}  // namespace ps::test
