// Catmull-Rom splines through (x[i], f[i]) on a non-uniform grid, with the end tangents taken
// as the one-sided differences (pbrt-v4 util/math: IntegrateCatmullRom, InvertCatmullRom):
// the integral of the spline, and the inverse of a monotone spline.
#pragma once
#include <algorithm>
#include <cmath>
#include <span>

namespace ps {

namespace catmull_rom_detail {
// The tangents at both ends of segment i, scaled to the segment's width (Hermite form).
inline void tangents(std::span<const float> x, std::span<const float> f, size_t i, float& d0, float& d1) {
    const float width = x[i + 1] - x[i];
    d0 = i > 0 ? width * (f[i + 1] - f[i - 1]) / (x[i + 1] - x[i - 1]) : f[i + 1] - f[i];
    d1 = i + 2 < x.size() ? width * (f[i + 2] - f[i]) / (x[i + 2] - x[i]) : f[i + 1] - f[i];
}
}  // namespace catmull_rom_detail

// The integral of the spline over [x.front(), x.back()] (x.size() >= 2): each Hermite
// segment integrates to width ((f0 + f1) / 2 + (d0 - d1) / 12).
inline float integrateCatmullRom(std::span<const float> x, std::span<const float> f) {
    float sum = 0;
    for (size_t i = 0; i + 1 < x.size(); ++i) {
        float d0, d1;
        catmull_rom_detail::tangents(x, f, i, d0, d1);
        sum += (x[i + 1] - x[i]) * ((f[i] + f[i + 1]) / 2 + (d0 - d1) / 12);
    }
    return sum;
}

// The x where the spline of increasing f reaches `value`, clamped to the grid's ends;
// Newton steps kept inside the segment by bisection.
inline float invertCatmullRom(std::span<const float> x, std::span<const float> f, float value) {
    if (!(value > f.front())) return x.front();
    if (!(value < f.back())) return x.back();
    // The last node whose f <= value; it precedes the end, since value < f.back().
    const size_t i = size_t(std::upper_bound(f.begin(), f.end(), value) - f.begin()) - 1;
    float d0, d1;
    catmull_rom_detail::tangents(x, f, i, d0, d1);
    const float f0 = f[i], f1 = f[i + 1];
    auto spline = [&](float t) {
        const float t2 = t * t, t3 = t2 * t;
        return (2 * t3 - 3 * t2 + 1) * f0 + (-2 * t3 + 3 * t2) * f1 + (t3 - 2 * t2 + t) * d0 + (t3 - t2) * d1 - value;
    };
    auto slope = [&](float t) {
        const float t2 = t * t;
        return (6 * t2 - 6 * t) * f0 + (-6 * t2 + 6 * t) * f1 + (3 * t2 - 4 * t + 1) * d0 + (3 * t2 - 2 * t) * d1;
    };
    float lo = 0, hi = 1, t = (value - f0) / (f1 - f0);
    for (int iter = 0; iter < 64; ++iter) {
        if (!(t > lo && t < hi)) t = (lo + hi) / 2;
        const float g = spline(t);
        if (std::fabs(g) < 1e-6f) break;
        (g < 0 ? lo : hi) = t;
        if (hi - lo < 1e-6f) break;
        t -= g / slope(t);
    }
    return x[i] + t * (x[i + 1] - x[i]);
}

}  // namespace ps
