// Warps from the unit square to directions and points, with their densities
// (thesis §2.4.1: sampling by inversion of the cumulative distribution).
#pragma once
#include "math/fast_trig.h"
#include "math/vec.h"

namespace ps {

// Shirley-Chiu concentric map: square [0,1)^2 -> unit disk, area preserving.
inline Vec2 sampleConcentricDisk(Vec2 u) {
    float ox = 2 * u.x - 1, oy = 2 * u.y - 1;
    if (ox == 0 && oy == 0) return {0, 0};
    float r, turns;  // the angle theta in turns: pi/4 is 1/8
    if (std::fabs(ox) > std::fabs(oy)) {
        r = ox;
        turns = 0.125f * (oy / ox);
    } else {
        r = oy;
        turns = 0.25f - 0.125f * (ox / oy);
    }
    return cosSinTurns(turns) * r;
}

// Cosine-weighted hemisphere around +z (Malley's method with the polar disk map:
// r^2 = u.x is uniform on the disk); pdf (solid angle) = cos(theta)/pi.
inline Vec3 sampleCosineHemisphere(Vec2 u) {
    float r = std::sqrt(u.x);
    Vec2 cs = cosSinTurns(u.y);
    return {r * cs.x, r * cs.y, safeSqrt(1 - u.x)};
}
inline float cosineHemispherePdf(float cosTheta) { return std::max(0.0f, cosTheta) * kInvPi; }

inline Vec3 sampleUniformSphere(Vec2 u) {
    float z = 1 - 2 * u.x;
    float r = safeSqrt(1 - z * z);
    Vec2 cs = cosSinTurns(u.y);
    return {r * cs.x, r * cs.y, z};
}
constexpr float uniformSpherePdf() { return kInv4Pi; }

inline Vec3 sampleUniformHemisphere(Vec2 u) {
    float z = u.x;
    float r = safeSqrt(1 - z * z);
    Vec2 cs = cosSinTurns(u.y);
    return {r * cs.x, r * cs.y, z};
}
constexpr float uniformHemispherePdf() { return kInv2Pi; }

// Uniform over the cone of directions within acos(cosMax) of +z.
inline Vec3 sampleUniformCone(Vec2 u, float cosMax) {
    float cosT = (1 - u.x) + u.x * cosMax;
    float sinT = safeSqrt(1 - cosT * cosT);
    Vec2 cs = cosSinTurns(u.y);
    return {sinT * cs.x, sinT * cs.y, cosT};
}
inline float uniformConePdf(float cosMax) { return 1 / (2 * kPi * (1 - cosMax)); }

// Uniform barycentrics (b0, b1) on a triangle; b2 = 1 - b0 - b1 (Heitz's low-distortion map).
// Written with selects rather than a branch: u is random, so a branch mispredicts half the time.
inline Vec2 sampleUniformTriangle(Vec2 u) {
    bool lower = u.x < u.y;
    float hx = u.x * 0.5f, hy = u.y * 0.5f;
    float b0 = lower ? hx : u.x - hy;
    float b1 = lower ? u.y - hx : hy;
    return {b0, b1};
}

// Solid-angle density from an area density: p_omega = p_A * d^2 / |cos theta_light| (thesis eq. 8.10).
inline float areaToSolidAngle(float pdfArea, float dist2, float absCosLight) {
    return absCosLight > 0 ? pdfArea * dist2 / absCosLight : 0.0f;
}

}  // namespace ps
