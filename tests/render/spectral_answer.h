// Exact expected pixel values in both colour modes for scenes whose RGB answer is a formula
// applied per channel to RGB parameters: in spectral mode the same formula applied per
// wavelength to the parameters' lifted spectra, integrated through the film's sensor
// (sensorRGB, checked in tests/spectral/sensor_test.cpp).
#pragma once
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "render_helpers.h"
#include "spectral/spectral_test_util.h"

namespace ps::test {

// An RGB scene parameter as each mode sees it: its RGB, and its spectrum times `scale`.
struct Lifted {
    std::array<float, 3> rgb;
    SpectrumSource spectrum;
    double scale = 1;
    double at(double lambda) const { return spectrum.at(float(lambda)) * scale; }
};

// "rgb L" / "rgb I": the RGB illuminant over its photometric integral (lights/light_spectrum.h).
inline Lifted emission(std::array<float, 3> rgb, const RGBColorSpace& space = srgbColorSpace()) {
    SpectrumSource s = SpectrumSource::rgbIlluminant(space, rgb);
    const double phi = s.photometric();
    return {rgb, std::move(s), 1 / phi};
}

// "rgb reflectance".
inline Lifted reflectance(std::array<float, 3> rgb, const RGBColorSpace& space = srgbColorSpace()) {
    return {rgb, SpectrumSource::rgbAlbedo(space, rgb), 1};
}

// The default film's sensor (cie1931, sRGB, imaging ratio 1).
inline const Sensor& srgbSensor() {
    static const Sensor s = Sensor::create({}, srgbColorSpace()).sensor;
    return s;
}

// f(p...) per channel of the parameters' RGB, or in spectral mode per wavelength of their
// spectra through the sensor.
template <class F, class... P>
std::array<double, 3> exactPixel(bool spectral, F f, const P&... p) {
    if (!spectral) return {f(double(p.rgb[0])...), f(double(p.rgb[1])...), f(double(p.rgb[2])...)};
    return sensorRGB(srgbSensor(), [&](double lambda) { return f(p.at(lambda)...); });
}

// The relative error allowed besides 4 sigma in spectral mode: single-precision arithmetic
// of the renderer and its sensor (the 1 nm sum itself is within 2e-5 of the sensor's
// continuous integral, sensor_test.cpp).
constexpr double kSpectralSystematic = 1e-4;

// Spectral mode's check of a render that is exact to float precision in RGB mode: the
// wavelengths add noise, so the region's mean is within 4 sigma (plus kSpectralSystematic) of
// `exact`, and sigma is under 0.2% of it, so that a 1% error fails.
inline void expectSpectralMean(const RegionStats& r, const std::array<double, 3>& exact, const std::string& what = "") {
    for (int c = 0; c < 3; ++c) {
        std::printf("  %s channel %d: %.6f +- %.6f, exact %.6f, %+.2f sigma\n", what.c_str(), c, r.mean[c], r.stdErr[c],
                    exact[c], (r.mean[c] - exact[c]) / std::max(r.stdErr[c], 1e-12));
        EXPECT_NEAR(r.mean[c], exact[c], 4 * r.stdErr[c] + kSpectralSystematic * std::fabs(exact[c]))
            << what << " channel " << c;
        EXPECT_LT(r.stdErr[c], 0.002 * std::fabs(exact[c])) << what << " channel " << c << ": too noisy to test";
    }
}

// Each channel of an image's mean within 4 sigma (plus kSpectralSystematic) of `exact`, with
// sigma small enough to catch a 2% error.
inline void expectImageMean(const RegionStats& s, const std::array<double, 3>& exact) {
    for (int c = 0; c < 3; ++c) {
        std::printf("  channel %d: %.5f +- %.5f, exact %.5f, %+.2f sigma\n", c, s.mean[c], s.stdErr[c], exact[c],
                    (s.mean[c] - exact[c]) / std::max(1e-12, s.stdErr[c]));
        EXPECT_NEAR(s.mean[c], exact[c], 4 * s.stdErr[c] + kSpectralSystematic * exact[c]) << "channel " << c;
        EXPECT_LT(4 * s.stdErr[c], 0.02 * exact[c]) << "channel " << c << ": cannot resolve a 2% error";
    }
}

// A render that is deterministic in RGB mode (every sample gives the exact value) is checked
// there to `rgbTolerance`; spectral mode adds the wavelengths' noise (expectSpectralMean).
inline void expectExact(const RegionStats& r, const std::array<double, 3>& exact, bool spectral,
                        double rgbTolerance = 1e-5) {
    if (spectral) return expectSpectralMean(r, exact);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.mean[c], exact[c], rgbTolerance) << "channel " << c;
}

// The formula of a light seen directly, for exactPixel.
inline double itself(double L) { return L; }

}  // namespace ps::test
