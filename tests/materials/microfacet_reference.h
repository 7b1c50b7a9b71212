// An independent reference for the rough BxDFs, for anchoring their values: the Torrance-
// Sparrow / Walter et al. 2007 microfacet BSDF with the Trowbridge-Reitz (GGX) distribution,
// Smith's height-correlated masking-shadowing G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz
// 2014, eq. 99; pbrt-v4 also uses it for transmission) and the Fresnel equations, written in
// double precision from the papers' formulas rather than from src/materials, and integrated by
// deterministic quadrature over the microfacet normals.
#pragma once
#include <cmath>
#include <complex>
#include <functional>

#include "math/vec.h"

namespace ps::test::ref {

struct V3 {
    double x, y, z;
};
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a) { return {-a.x, -a.y, -a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 unit(V3 a) { return (1 / std::sqrt(dot(a, a))) * a; }
inline V3 fromVec(Vec3 v) { return unit({v.x, v.y, v.z}); }
inline Vec3 toVec(V3 v) { return Vec3(float(v.x), float(v.y), float(v.z)); }

// GGX with roughnesses along x and y; normals m in the upper hemisphere (Heitz 2014, eq. 85
// written with the components of m).
struct GGX {
    double ax, ay;
    double D(V3 m) const {
        if (m.z <= 0) return 0;
        double e = m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay) + m.z * m.z;
        return 1 / (M_PI * ax * ay * e * e);
    }
    // Smith's Lambda for GGX (Heitz 2014, eq. 86): (-1 + sqrt(1 + 1/a^2)) / 2 with
    // 1/a^2 = alpha(phi)^2 tan^2(theta).
    double lambda(V3 w) const {
        double invA2 = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / (w.z * w.z);
        return (std::sqrt(1 + invA2) - 1) / 2;
    }
    double G2(V3 wo, V3 wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }
};

// Unpolarised Fresnel reflectance for light meeting the interface at cos ci > 0 from the
// medium of index n1, the other side having n2 (total internal reflection gives 1).
inline double fresnelDielectric(double ci, double n1, double n2) {
    double s2t = (n1 / n2) * (n1 / n2) * (1 - ci * ci);
    if (s2t >= 1) return 1;
    double ct = std::sqrt(1 - s2t);
    double rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct), rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
    return (rs * rs + rp * rp) / 2;
}

// Conductor of complex index eta + i k seen from a medium of index 1, in the real-arithmetic
// form (a^2 + b^2 = |n^2 - sin^2|) of the textbook derivation.
inline double fresnelConductor(double ci, double eta, double k) {
    double c2 = ci * ci, s2 = 1 - c2;
    double t = eta * eta - k * k - s2;
    double a2b2 = std::sqrt(t * t + 4 * eta * eta * k * k);
    double a = std::sqrt(std::max(0.0, (a2b2 + t) / 2));
    double rs = (a2b2 - 2 * a * ci + c2) / (a2b2 + 2 * a * ci + c2);
    double rp = rs * (c2 * a2b2 - 2 * a * ci * s2 + s2 * s2) / (c2 * a2b2 + 2 * a * ci * s2 + s2 * s2);
    return (rs + rp) / 2;
}

// Quadrature over microfacet normals: slopes (p, q) = (ax r cos phi, ay r sin phi) with
// r = s / (1 - s), midpoint rule in (s, phi) on nS x nPhi points, so the resolution follows
// the lobe for any roughness. Calls visit(m, dOmega_m) for each node (m on the upper
// hemisphere; dOmega_m = cos^3(theta_m) dp dq).
inline void forEachNormal(const GGX& g, int nS, int nPhi, const std::function<void(V3, double)>& visit) {
    for (int i = 0; i < nS; ++i) {
        double s = (i + 0.5) / nS, r = s / (1 - s), drds = 1 / ((1 - s) * (1 - s));
        for (int j = 0; j < nPhi; ++j) {
            double phi = (j + 0.5) / nPhi * 2 * M_PI;
            double p = g.ax * r * std::cos(phi), q = g.ay * r * std::sin(phi);
            double c = 1 / std::sqrt(1 + p * p + q * q);
            visit(c * V3{-p, -q, 1}, c * c * c * g.ax * g.ay * r * drds * (1.0 / nS) * (2 * M_PI / nPhi));
        }
    }
}

// One scattering of wo at the microfacet m (oriented to wo's side): the outgoing direction,
// its solid angle per solid angle of m, and the reference BSDF value in both transport modes.
struct Scatter {
    bool valid = false, transmission = false;
    V3 wi{0, 0, 0};
    double dOmegaI_dOmegaM = 0;
    double fRadiance = 0, fImportance = 0;  // times |cos wi| gives the albedo integrand
};

// Rough dielectric between index 1 (above, +z) and eta (below); conductors use eta = 0 and
// fresnelR. reflect/refract per Walter et al. 2007 eqs. 13-21.
inline Scatter reflectAt(const GGX& g, V3 wo, V3 m, double F) {
    Scatter r;
    double c = dot(wo, m);
    if (c <= 0) return r;
    r.wi = (2 * c) * m + -wo;
    if (r.wi.z * wo.z <= 0) return r;
    r.valid = true;
    r.dOmegaI_dOmegaM = 4 * c;
    double f = F * g.D(m.z > 0 ? m : -m) * g.G2(wo, r.wi) / (4 * std::fabs(wo.z * r.wi.z));
    r.fRadiance = r.fImportance = f;
    return r;
}

inline Scatter refractAt(const GGX& g, V3 wo, V3 m, double nO, double nI) {
    Scatter r;
    double c = dot(wo, m), ratio = nO / nI;
    if (c <= 0) return r;
    double s2t = ratio * ratio * (1 - c * c);
    if (s2t >= 1) return r;  // total internal reflection
    r.wi = (-ratio) * wo + (ratio * c - std::sqrt(1 - s2t)) * m;
    if (r.wi.z * wo.z >= 0) return r;
    r.valid = r.transmission = true;
    double oh = dot(wo, m), ih = dot(r.wi, m), sum = nO * oh + nI * ih;
    r.dOmegaI_dOmegaM = sum * sum / (nI * nI * std::fabs(ih));
    double F = fresnelDielectric(c, nO, nI);
    double common = std::fabs(ih * oh) / std::fabs(r.wi.z * wo.z) * (1 - F) * g.G2(wo, r.wi) * g.D(m.z > 0 ? m : -m) / (sum * sum);
    r.fRadiance = nO * nO * common;    // radiance arriving along wi, leaving along wo
    r.fImportance = nI * nI * common;  // the adjoint: f(wi, wo)
    return r;
}

}  // namespace ps::test::ref
