#include "scene/color_space.h"
#include "math/matrix3.h"

#include <algorithm>
#include <cctype>

namespace ps {

namespace {

std::array<double, 3> xyzOf(const double xy[2]) { return {xy[0] / xy[1], 1.0, (1 - xy[0] - xy[1]) / xy[1]}; }

// RGB -> XYZ: the primaries' XYZ as columns, scaled so that RGB (1,1,1) is the white at Y = 1.
Matrix3 toXYZ(const RGBColorSpace& s) {
    Matrix3 p;
    for (int c = 0; c < 3; ++c) {
        const auto v = xyzOf(s.primaries[c]);
        for (int r = 0; r < 3; ++r) p.a[r][c] = v[size_t(r)];
    }
    const auto scale = p.inverse() * xyzOf(s.white);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) p.a[r][c] *= scale[size_t(c)];
    return p;
}

// Bradford chromatic adaptation of XYZ from one white to another.
Matrix3 bradford(const double from[2], const double to[2]) {
    const Matrix3 m{{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
    const auto a = m * xyzOf(from), b = m * xyzOf(to);
    const Matrix3 scale{{{b[0] / a[0], 0, 0}, {0, b[1] / a[1], 0}, {0, 0, b[2] / a[2]}}};
    return m.inverse() * (scale * m);
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
    Matrix3 m = toXYZ(*space);
    if (kind != SpectrumKind::Illuminant) m = bradford(space->white, srgb.white) * m;
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
