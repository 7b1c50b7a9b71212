#include "scene/color_space.h"

#include <algorithm>
#include <cctype>

namespace ps {

namespace {

using Mat3 = std::array<double, 9>;

Mat3 multiply(const Mat3& a, const Mat3& b) {
    Mat3 c{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) c[size_t(3 * i + j)] += a[size_t(3 * i + k)] * b[size_t(3 * k + j)];
    return c;
}

Mat3 inverse(const Mat3& m) {
    const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7], i = m[8];
    const double A = e * i - f * h, B = f * g - d * i, C = d * h - e * g;
    const double det = a * A + b * B + c * C;
    return {A / det, (c * h - b * i) / det, (b * f - c * e) / det,
            B / det, (a * i - c * g) / det, (c * d - a * f) / det,
            C / det, (b * g - a * h) / det, (a * e - b * d) / det};
}

std::array<double, 3> apply(const Mat3& m, std::array<double, 3> v) {
    return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
            m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

std::array<double, 3> xyzOf(const double xy[2]) { return {xy[0] / xy[1], 1.0, (1 - xy[0] - xy[1]) / xy[1]}; }

// RGB -> XYZ: the primaries' XYZ as columns, scaled so that RGB (1,1,1) is the white at Y = 1.
Mat3 toXYZ(const RGBColorSpace& s) {
    Mat3 p{};
    for (int c = 0; c < 3; ++c) {
        const auto v = xyzOf(s.primaries[c]);
        for (int r = 0; r < 3; ++r) p[size_t(3 * r + c)] = v[size_t(r)];
    }
    const auto scale = apply(inverse(p), xyzOf(s.white));
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) p[size_t(3 * r + c)] *= scale[size_t(c)];
    return p;
}

// Bradford chromatic adaptation of XYZ from one white to another.
Mat3 bradford(const double from[2], const double to[2]) {
    const Mat3 m{0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296};
    const auto a = apply(m, xyzOf(from)), b = apply(m, xyzOf(to));
    const Mat3 scale{b[0] / a[0], 0, 0, 0, b[1] / a[1], 0, 0, 0, b[2] / a[2]};
    return multiply(inverse(m), multiply(scale, m));
}

const RGBColorSpace kSpaces[] = {
    {"srgb", {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}}, {0.3127, 0.3290}},
    {"rec2020", {{0.708, 0.292}, {0.170, 0.797}, {0.131, 0.046}}, {0.3127, 0.3290}},
    {"dci-p3", {{0.680, 0.320}, {0.265, 0.690}, {0.150, 0.060}}, {0.3127, 0.3290}},
    {"aces2065-1", {{0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.077}}, {0.32168, 0.33767}},
};

}  // namespace

const RGBColorSpace& srgbColorSpace() { return kSpaces[0]; }

const RGBColorSpace* namedColorSpace(const std::string& name) {
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    for (const RGBColorSpace& s : kSpaces)
        if (lower == s.name) return &s;
    return nullptr;
}

Spectrum toRenderingSpace(Spectrum rgb, const RGBColorSpace* space, SpectrumKind kind) {
    if (!space || space == &srgbColorSpace()) return rgb;
    const RGBColorSpace& srgb = srgbColorSpace();
    Mat3 m = toXYZ(*space);
    if (kind != SpectrumKind::Illuminant) m = multiply(bradford(space->white, srgb.white), m);
    m = multiply(inverse(toXYZ(srgb)), m);
    const auto v = apply(m, {double(rgb.r), double(rgb.g), double(rgb.b)});
    const double hi = kind == SpectrumKind::Albedo ? 1.0 : 1e30;
    return {float(std::clamp(v[0], 0.0, hi)), float(std::clamp(v[1], 0.0, hi)), float(std::clamp(v[2], 0.0, hi))};
}

std::array<float, 9> outputFromRenderingSpace(const RGBColorSpace& space) {
    const Mat3 m = multiply(inverse(toXYZ(space)), toXYZ(srgbColorSpace()));
    std::array<float, 9> out{};
    for (size_t k = 0; k < 9; ++k) out[k] = float(m[k]);
    return out;
}

}  // namespace ps
