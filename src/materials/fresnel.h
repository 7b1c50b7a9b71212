// Fresnel reflectance of smooth dielectric and conductor interfaces.
#pragma once
#include <algorithm>
#include <cmath>
#include <complex>
#include "math/spectrum.h"
#include "math/vec.h"

namespace ps {

// Unpolarised reflectance for light arriving at cosThetaI from the side the normal points
// into; eta is the relative index of the other side. Negative cosines mean arriving from
// inside, handled by inverting eta. Returns 1 under total internal reflection.
inline float fresnelDielectric(float cosThetaI, float eta) {
    cosThetaI = clampf(cosThetaI, -1, 1);
    if (cosThetaI < 0) {
        eta = 1 / eta;
        cosThetaI = -cosThetaI;
    }
    float sin2T = (1 - cosThetaI * cosThetaI) / (eta * eta);
    if (sin2T >= 1) return 1;
    float cosT = safeSqrt(1 - sin2T);
    float rParl = (eta * cosThetaI - cosT) / (eta * cosThetaI + cosT);
    float rPerp = (cosThetaI - eta * cosT) / (cosThetaI + eta * cosT);
    return (rParl * rParl + rPerp * rPerp) / 2;
}

// Conductor with complex index eta + i k (per channel). The complex arithmetic is written
// out: std::complex's division and square root are library calls that guard infinities and
// NaNs, several percent of a render with metals (none can arise here for eta != 0).
inline float fresnelComplex(float cosThetaI, std::complex<float> eta) {
    cosThetaI = clampf(cosThetaI, 0, 1);
    const float n = eta.real(), k = eta.imag();
    const float eta2r = n * n - k * k, eta2i = 2 * n * k;  // eta^2
    const float eta2Norm = eta2r * eta2r + eta2i * eta2i;
    if (!(eta2Norm > 0)) return 1;
    // cosT = sqrt(1 - sin2T), sin2T = sin2I / eta^2; the principal square root.
    const float scale = (1 - cosThetaI * cosThetaI) / eta2Norm;
    const float zr = 1 - eta2r * scale, zi = eta2i * scale;
    // (The larger part from |z| + |zr|, the other by division: no cancellation.)
    const float t = std::sqrt((std::sqrt(zr * zr + zi * zi) + std::fabs(zr)) / 2);
    const float cr = zr >= 0 ? t : std::fabs(zi) / (2 * t);
    const float ci = zr >= 0 ? (t > 0 ? zi / (2 * t) : 0.0f) : std::copysign(t, zi);
    auto norm2 = [](float re, float im) { return re * re + im * im; };
    // |rParl|^2 = |eta cosI - cosT|^2 / |eta cosI + cosT|^2
    const float ar = n * cosThetaI, ai = k * cosThetaI;
    const float parl = norm2(ar - cr, ai - ci) / norm2(ar + cr, ai + ci);
    // |rPerp|^2 = |cosI - eta cosT|^2 / |cosI + eta cosT|^2
    const float br = n * cr - k * ci, bi = n * ci + k * cr;
    const float perp = norm2(cosThetaI - br, bi) / norm2(cosThetaI + br, bi);
    return (parl + perp) / 2;
}

// Per channel: r, g, b in RGB mode (whose fourth channel repeats g), four wavelengths in
// spectral mode.
inline Spectrum fresnelComplex(float cosThetaI, const Spectrum& eta, const Spectrum& k) {
    const float g = fresnelComplex(cosThetaI, {eta.g, k.g});
    const float c3 = eta.c3 == eta.g && k.c3 == k.g ? g : fresnelComplex(cosThetaI, {eta.c3, k.c3});
    return Spectrum::sampled(fresnelComplex(cosThetaI, {eta.r, k.r}), g, fresnelComplex(cosThetaI, {eta.b, k.b}), c3);
}

inline Vec3 reflect(Vec3 wo, Vec3 n) { return -wo + n * (2 * dot(wo, n)); }

// Refraction of wi through the interface with normal n and relative index eta (of the
// side opposite n). On success sets wt and the relative index actually crossed.
inline bool refract(Vec3 wi, Vec3 n, float eta, float* etap, Vec3* wt) {
    float cosI = dot(n, wi);
    if (cosI < 0) {
        eta = 1 / eta;
        cosI = -cosI;
        n = -n;
    }
    float sin2I = std::max(0.0f, 1 - cosI * cosI);
    float sin2T = sin2I / (eta * eta);
    if (sin2T >= 1) return false;
    float cosT = safeSqrt(1 - sin2T);
    *wt = -wi / eta + n * (cosI / eta - cosT);
    if (etap) *etap = eta;
    return true;
}

}  // namespace ps
