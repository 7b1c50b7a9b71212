#include "scene/color_space.h"
#include "math/matrix3.h"
#include "spectral/colorimetry.h"
#include "spectral/sensor.h"  // whiteBalanceMatrix: the Bradford adaptation

#include <algorithm>

namespace ps {

namespace {

std::array<double, 3> xyzOf(const double xy[2]) { return xyzFromChromaticity(xy[0], xy[1]); }

// RGB -> XYZ: the primaries' XYZ as columns, scaled so that RGB (1,1,1) is the white at Y = 1.
Matrix3 toXYZ(const RGBColorSpace& s) { return xyzFromRGBMatrix(s.primaries, xyzOf(s.white)); }

}  // namespace

Spectrum toRenderingSpace(Spectrum rgb, const RGBColorSpace* space, SpectrumKind kind) {
    if (!space || space == &srgbColorSpace()) return rgb;
    const RGBColorSpace& srgb = srgbColorSpace();
    Matrix3 m = toXYZ(*space);
    if (kind != SpectrumKind::Illuminant) m = whiteBalanceMatrix(space->white, srgb.white) * m;
    m = toXYZ(srgb).inverse() * m;
    const auto v = m * std::array<double, 3>{double(rgb.r), double(rgb.g), double(rgb.b)};
    const double hi = kind == SpectrumKind::Albedo ? 1.0 : 1e30;
    return {float(std::clamp(v[0], 0.0, hi)), float(std::clamp(v[1], 0.0, hi)), float(std::clamp(v[2], 0.0, hi))};
}

std::array<float, 9> outputFromRenderingSpace(const RGBColorSpace& space) {
    const Matrix3 m = toXYZ(space).inverse() * toXYZ(srgbColorSpace());
    std::array<float, 9> out{};
    for (size_t k = 0; k < 9; ++k) out[k] = float(m.a[k / 3][k % 3]);
    return out;
}

}  // namespace ps
