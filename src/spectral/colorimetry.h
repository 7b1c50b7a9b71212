// Spectral colorimetry of an RGB colour space as pbrt-v4 computes it (RGBColorSpace
// constructor): the white is the chromaticity of the standard illuminant's spectrum (not the
// nominal one), and RGB (1,1,1) is that white at Y = 1.
#pragma once
#include <array>

#include "math/matrix3.h"
#include "spectral/cie.h"
#include "spectral/rgb_color_space.h"

namespace ps {

// A spectrum sampled at the whole nanometres 360..830 and looked up at the nearest one
// (pbrt-v4's DenselySampledSpectrum).
struct DenseSpectrum {
    std::array<float, kCieSamples> value{};
    float at(float lambda) const { return denseLookup(value.data(), lambda); }
    float maxValue() const;
};

using XYZ = std::array<double, 3>;

// XYZ of chromaticity (x, y) at luminance Y.
XYZ xyzFromChromaticity(double x, double y, double Y = 1);

// sum over the 1 nm grid of the matching functions times a dense spectrum, / kCieYIntegral
// (pbrt-v4's SpectrumToXYZ: a spectrum with the luminance of a flat 1 has Y = 1).
XYZ denseSpectrumToXYZ(const DenseSpectrum& s);

struct Colorimetry {
    DenseSpectrum illuminant;  // normalised: sum ybar * illuminant = kCieYIntegral
    double white[2];           // chromaticity of `illuminant`
    Matrix3 xyzFromRGB, rgbFromXYZ;
};

// Computed once per space and kept.
const Colorimetry& colorimetry(const RGBColorSpace& space);

// RGB -> XYZ matrix of primaries (x, y) whose (1,1,1) is `whiteXYZ`.
Matrix3 xyzFromRGBMatrix(const double primaries[3][2], const XYZ& whiteXYZ);

}  // namespace ps
