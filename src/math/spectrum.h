// The colour carried along paths: one type for both colour modes, so that no integrator is
// templated on a colour type.
//
// A Spectrum is four floats. In RGB mode (`--color rgb`) channels 0..2 are linear r, g, b of
// the rendering space (linear sRGB) and channel 3 is a copy of g: every constructor keeps
// that copy and every operation is per channel, so the copy survives arithmetic and the
// four-channel max / isBlack / isFinite equal the three-channel ones (RGB images are
// unchanged by the fourth channel). In spectral mode (`--color spectral`) channel i is the
// value at the path's wavelength i; the wavelengths (spectral/wavelengths.h) travel with the
// camera sample and are passed, as a pointer that is null in RGB mode, wherever a scene
// spectrum is evaluated (textures, materials, light emission). Only the film's sensor turns
// spectral values into colour (transport/spectral_film.h).
#pragma once
#include <algorithm>
#include <cmath>

namespace ps {

struct Spectrum {
    float r = 0, g = 0, b = 0;
    float c3 = 0;  // the fourth wavelength's value; g in RGB mode
    Spectrum() = default;
    constexpr explicit Spectrum(float v) : r(v), g(v), b(v), c3(v) {}
    constexpr Spectrum(float r_, float g_, float b_) : r(r_), g(g_), b(b_), c3(g_) {}
    // Values at four sampled wavelengths (spectral mode).
    static constexpr Spectrum sampled(float v0, float v1, float v2, float v3) {
        Spectrum s(v0, v1, v2);
        s.c3 = v3;
        return s;
    }
    float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : (i == 2 ? b : c3)); }
    float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : (i == 2 ? b : c3)); }
    Spectrum& operator+=(const Spectrum& o) { r += o.r; g += o.g; b += o.b; c3 += o.c3; return *this; }
    Spectrum& operator*=(const Spectrum& o) { r *= o.r; g *= o.g; b *= o.b; c3 *= o.c3; return *this; }
    Spectrum& operator*=(float s) { r *= s; g *= s; b *= s; c3 *= s; return *this; }
    Spectrum& operator/=(float s) { return *this *= (1.0f / s); }
    bool isBlack() const { return r == 0 && g == 0 && b == 0 && c3 == 0; }
    bool isFinite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b) && std::isfinite(c3); }
    float maxComponent() const { return std::max(std::max(r, g), std::max(b, c3)); }
    // RGB mode only (the mean and luminance of sampled values mean nothing without their
    // wavelengths; the film's sensor converts those).
    float average() const { return (r + g + b) * (1.0f / 3.0f); }
    // Luminance Y of linear sRGB / Rec.709 primaries.
    float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
};
inline Spectrum operator+(Spectrum a, const Spectrum& b) { return a += b; }
inline Spectrum operator-(const Spectrum& a, const Spectrum& b) {
    return Spectrum::sampled(a.r - b.r, a.g - b.g, a.b - b.b, a.c3 - b.c3);
}
inline Spectrum operator*(Spectrum a, const Spectrum& b) { return a *= b; }
inline Spectrum operator*(Spectrum a, float s) { return a *= s; }
inline Spectrum operator*(float s, Spectrum a) { return a *= s; }
inline Spectrum operator/(Spectrum a, float s) { return a /= s; }
inline Spectrum operator/(const Spectrum& a, const Spectrum& b) {
    auto d = [](float x, float y) { return y != 0 ? x / y : 0.0f; };
    return Spectrum::sampled(d(a.r, b.r), d(a.g, b.g), d(a.b, b.b), d(a.c3, b.c3));
}
inline Spectrum sqrt(const Spectrum& a) {
    return Spectrum::sampled(std::sqrt(a.r), std::sqrt(a.g), std::sqrt(a.b), std::sqrt(a.c3));
}
inline Spectrum exp(const Spectrum& a) { return Spectrum::sampled(std::exp(a.r), std::exp(a.g), std::exp(a.b), std::exp(a.c3)); }
inline Spectrum clamp(const Spectrum& a, float lo, float hi) {
    return Spectrum::sampled(std::clamp(a.r, lo, hi), std::clamp(a.g, lo, hi), std::clamp(a.b, lo, hi), std::clamp(a.c3, lo, hi));
}

}  // namespace ps
