// The film's sensor (pbrt-v4's PixelSensor with its default "cie1931" sensor): converts the
// radiance a path carries at its sampled wavelengths to XYZ and then to the output colour
// space's linear RGB.
#pragma once
#include <array>
#include <string>

#include "math/matrix3.h"
#include "spectral/rgb_color_space.h"
#include "spectral/wavelengths.h"

namespace ps {

struct SensorSettings {
    std::string name = "cie1931";  // Film "sensor"
    float iso = 100;               // Film "iso"
    float exposureTime = 1;        // camera shutterclose - shutteropen
    float whiteBalance = 0;        // Film "whitebalance" (kelvin); 0 = none
};

class Sensor {
  public:
    struct Created;
    // A sensor for `settings` writing `output`. pbrt-v4's measured camera sensors (e.g.
    // "canon_eos_100d") are not supported: the result is the cie1931 sensor and
    // `unsupported` says so, for the caller to warn.
    static Created create(const SensorSettings& settings, const RGBColorSpace& output);

    // The Monte Carlo estimate of imagingRatio * integral of xbar, ybar, zbar times L: the
    // average over the wavelengths of cmf(lambda) L / pdf (a zero pdf counts as 0, which
    // is how terminated secondary wavelengths drop out). Like pbrt-v4's film, it is NOT
    // divided by the Y integral: lights are normalised by their photometric integral
    // instead, so that RGB (1,1,1) emission gives Y = 1.
    std::array<double, 3> toSensorXYZ(const SpectralValues& L, const SampledWavelengths& w) const;
    // Output linear RGB: the white-balanced XYZ in the output space.
    std::array<double, 3> toOutputRGB(const SpectralValues& L, const SampledWavelengths& w) const;

    float imagingRatio() const { return imagingRatio_; }
    // Output RGB from sensor XYZ: RGBFromXYZ(output) * whiteBalance.
    const Matrix3& outputFromSensor() const { return outputFromSensor_; }
    const Matrix3& whiteBalance() const { return whiteBalance_; }

  private:
    float imagingRatio_ = 1;
    Matrix3 whiteBalance_, outputFromSensor_;
};

struct Sensor::Created {
    Sensor sensor;
    std::string unsupported;  // empty, or why the named sensor was replaced by cie1931
};

// pbrt-v4's von Kries adaptation in the Bradford LMS space: XYZ of white `from` (x, y) is
// mapped to XYZ of white `to`.
Matrix3 whiteBalanceMatrix(const double from[2], const double to[2]);

}  // namespace ps
