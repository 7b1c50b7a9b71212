#include "spectral/sensor.h"
#include "spectral/cie.h"
#include "spectral/colorimetry.h"
#include "spectral/spectrum_source.h"

namespace ps {

Matrix3 whiteBalanceMatrix(const double from[2], const double to[2]) {
    // Bradford's cone-response matrix (Lam 1985), as in pbrt-v4's LMSFromXYZ.
    const Matrix3 lmsFromXYZ{{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
    const auto a = lmsFromXYZ * xyzFromChromaticity(from[0], from[1]);
    const auto b = lmsFromXYZ * xyzFromChromaticity(to[0], to[1]);
    const Matrix3 scale{{{b[0] / a[0], 0, 0}, {0, b[1] / a[1], 0}, {0, 0, b[2] / a[2]}}};
    return lmsFromXYZ.inverse() * (scale * lmsFromXYZ);
}

Sensor::Created Sensor::create(const SensorSettings& s, const RGBColorSpace& output) {
    Created c;
    if (s.name != "cie1931")
        c.unsupported = "sensor \"" + s.name + "\" is not supported; the \"cie1931\" sensor is used";
    Sensor& sensor = c.sensor;
    // pbrt-v4's imaging ratio; the defaults (1 s, ISO 100) make it exactly 1.
    sensor.imagingRatio_ = s.exposureTime * s.iso / 100;
    if (s.whiteBalance != 0) {
        // From the white of the daylight illuminant at that temperature to the output
        // space's white (the chromaticity of its illuminant spectrum).
        const XYZ src = denseSpectrumToXYZ(daylightSpectrum(s.whiteBalance));
        const double sum = src[0] + src[1] + src[2];
        const double from[2] = {src[0] / sum, src[1] / sum};
        sensor.whiteBalance_ = whiteBalanceMatrix(from, colorimetry(output).white);
    }
    sensor.outputFromSensor_ = colorimetry(output).rgbFromXYZ * sensor.whiteBalance_;
    return c;
}

std::array<double, 3> Sensor::toSensorXYZ(const SpectralValues& L, const SampledWavelengths& w) const {
    std::array<double, 3> xyz{0, 0, 0};
    for (int i = 0; i < kWavelengthSamples; ++i) {
        const float pdf = w.pdf[size_t(i)];
        if (pdf == 0) continue;
        const int k = cieIndex(w.lambda[size_t(i)]);
        if (k < 0) continue;
        const double v = double(L[size_t(i)]) / pdf;
        xyz[0] += kCieX[k] * v;
        xyz[1] += kCieY[k] * v;
        xyz[2] += kCieZ[k] * v;
    }
    for (double& v : xyz) v *= double(imagingRatio_) / kWavelengthSamples;
    return xyz;
}

std::array<double, 3> Sensor::toOutputRGB(const SpectralValues& L, const SampledWavelengths& w) const {
    return outputFromSensor_ * toSensorXYZ(L, w);
}

}  // namespace ps
