// Fresnel reflectance of smooth dielectric and conductor interfaces.
#pragma once
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

// Conductor with complex index eta + i k (per channel).
inline float fresnelComplex(float cosThetaI, std::complex<float> eta) {
    using C = std::complex<float>;
    cosThetaI = clampf(cosThetaI, 0, 1);
    float sin2I = 1 - cosThetaI * cosThetaI;
    C sin2T = sin2I / (eta * eta);
    C cosT = std::sqrt(C(1) - sin2T);
    C rParl = (eta * cosThetaI - cosT) / (eta * cosThetaI + cosT);
    C rPerp = (C(cosThetaI) - eta * cosT) / (C(cosThetaI) + eta * cosT);
    return (std::norm(rParl) + std::norm(rPerp)) / 2;
}

inline Spectrum fresnelComplex(float cosThetaI, const Spectrum& eta, const Spectrum& k) {
    return {fresnelComplex(cosThetaI, {eta.r, k.r}), fresnelComplex(cosThetaI, {eta.g, k.g}),
            fresnelComplex(cosThetaI, {eta.b, k.b})};
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
