// Layout of an RGB-to-spectrum coefficient table (Jakob & Hanika 2019 at pbrt-v4's
// resolution), shared by the generator that writes it and the lookup that reads it.
//
// For RGB with largest component z = rgb[m], the other two are x = rgb[(m+1)%3] / z and
// y = rgb[(m+2)%3] / z in [0,1]. Entry [m][k][j][i] holds the sigmoid-polynomial
// coefficients (c0, c1, c2) of c0 lambda^2 + c1 lambda + c2 (lambda in nm) for z = the
// k-th brightness node, y = j/(res-1), x = i/(res-1).
#pragma once
#include <cstddef>

namespace ps {

constexpr int kRgbTableRes = 64;
constexpr size_t kRgbTableFloats = size_t(3) * kRgbTableRes * kRgbTableRes * kRgbTableRes * 3;

constexpr size_t rgbTableIndex(int m, int k, int j, int i) {
    return ((((size_t(m) * kRgbTableRes + size_t(k)) * kRgbTableRes + size_t(j)) * kRgbTableRes) + size_t(i)) * 3;
}

// The brightness nodes crowd towards 0 and 1, where the coefficients change fastest:
// smoothstep(smoothstep(k / (res - 1))), as pbrt-v4's tables.
inline float rgbTableBrightness(int k) {
    const double x = double(k) / (kRgbTableRes - 1);
    auto smoothstep = [](double v) { return v * v * (3 - 2 * v); };
    return float(smoothstep(smoothstep(x)));
}

}  // namespace ps
