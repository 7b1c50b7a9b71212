// The colour carried along paths. RGB for now (linear, the scene's colour space); every
// radiometric quantity goes through this one type so a spectral mode can replace it.
#pragma once
#include <algorithm>
#include <cmath>

namespace ps {

struct Spectrum {
    float r = 0, g = 0, b = 0;
    Spectrum() = default;
    constexpr explicit Spectrum(float v) : r(v), g(v), b(v) {}
    constexpr Spectrum(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
    float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
    Spectrum& operator+=(const Spectrum& o) { r += o.r; g += o.g; b += o.b; return *this; }
    Spectrum& operator*=(const Spectrum& o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
    Spectrum& operator*=(float s) { r *= s; g *= s; b *= s; return *this; }
    Spectrum& operator/=(float s) { return *this *= (1.0f / s); }
    bool isBlack() const { return r == 0 && g == 0 && b == 0; }
    bool isFinite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
    float maxComponent() const { return std::max(r, std::max(g, b)); }
    float average() const { return (r + g + b) * (1.0f / 3.0f); }
    // Luminance Y of linear sRGB / Rec.709 primaries.
    float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
};
inline Spectrum operator+(Spectrum a, const Spectrum& b) { return a += b; }
inline Spectrum operator-(const Spectrum& a, const Spectrum& b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
inline Spectrum operator*(Spectrum a, const Spectrum& b) { return a *= b; }
inline Spectrum operator*(Spectrum a, float s) { return a *= s; }
inline Spectrum operator*(float s, Spectrum a) { return a *= s; }
inline Spectrum operator/(Spectrum a, float s) { return a /= s; }
inline Spectrum operator/(const Spectrum& a, const Spectrum& b) {
    auto d = [](float x, float y) { return y != 0 ? x / y : 0.0f; };
    return {d(a.r, b.r), d(a.g, b.g), d(a.b, b.b)};
}
inline Spectrum sqrt(const Spectrum& a) { return {std::sqrt(a.r), std::sqrt(a.g), std::sqrt(a.b)}; }
inline Spectrum exp(const Spectrum& a) { return {std::exp(a.r), std::exp(a.g), std::exp(a.b)}; }
inline Spectrum clamp(const Spectrum& a, float lo, float hi) {
    return {std::clamp(a.r, lo, hi), std::clamp(a.g, lo, hi), std::clamp(a.b, lo, hi)};
}

}  // namespace ps
