#include "spectral/colorimetry.h"
#include "spectral/illuminant_data.h"
#include "spectral/piecewise_linear.h"

#include <algorithm>
#include <memory>
#include <mutex>

namespace ps {

float DenseSpectrum::maxValue() const { return *std::max_element(value.begin(), value.end()); }

XYZ xyzFromChromaticity(double x, double y, double Y) {
    if (y == 0) return {0, 0, 0};
    return {x * Y / y, Y, (1 - x - y) * Y / y};
}

XYZ denseSpectrumToXYZ(const DenseSpectrum& s) {
    XYZ xyz{0, 0, 0};
    for (int i = 0; i < kCieSamples; ++i) {
        xyz[0] += double(kCieX[i]) * s.value[i];
        xyz[1] += double(kCieY[i]) * s.value[i];
        xyz[2] += double(kCieZ[i]) * s.value[i];
    }
    for (double& v : xyz) v /= kCieYIntegral;
    return xyz;
}

Matrix3 xyzFromRGBMatrix(const double primaries[3][2], const XYZ& whiteXYZ) {
    Matrix3 p;
    for (int c = 0; c < 3; ++c) {
        const XYZ v = xyzFromChromaticity(primaries[c][0], primaries[c][1]);
        for (int r = 0; r < 3; ++r) p.a[r][c] = v[size_t(r)];
    }
    const auto scale = p.inverse() * whiteXYZ;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) p.a[r][c] *= scale[size_t(c)];
    return p;
}

namespace {

Colorimetry build(const RGBColorSpace& space) {
    Colorimetry c;
    const PiecewiseLinearTable t = PiecewiseLinearTable::fromInterleaved(standardIlluminantPairs(space.illuminant), true);
    for (int i = 0; i < kCieSamples; ++i) c.illuminant.value[i] = t.at(float(kCieLambdaMin + i));
    const XYZ w = denseSpectrumToXYZ(c.illuminant);
    const double sum = w[0] + w[1] + w[2];
    c.white[0] = w[0] / sum;
    c.white[1] = w[1] / sum;
    // pbrt-v4 builds the matrix from the illuminant's own XYZ (its Y is 1 to float precision).
    c.xyzFromRGB = xyzFromRGBMatrix(space.primaries, w);
    c.rgbFromXYZ = c.xyzFromRGB.inverse();
    return c;
}

}  // namespace

const Colorimetry& colorimetry(const RGBColorSpace& space) {
    static std::unique_ptr<Colorimetry> cache[kNamedColorSpaces];
    static std::once_flag once[kNamedColorSpaces];
    std::call_once(once[space.index], [&] { cache[space.index] = std::make_unique<Colorimetry>(build(space)); });
    return *cache[space.index];
}

}  // namespace ps
