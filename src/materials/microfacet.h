// The Trowbridge-Reitz (GGX) microfacet distribution with Smith's height-correlated
// masking-shadowing and sampling of visible normals (Heitz 2018).
#pragma once
#include "math/frame.h"
#include "math/fast_trig.h"
#include "math/vec.h"

namespace ps {

class TrowbridgeReitz {
public:
    TrowbridgeReitz(float alphaX, float alphaY) : ax_(alphaX), ay_(alphaY) {
        if (!effectivelySmooth()) {
            ax_ = std::max(ax_, 1e-4f);
            ay_ = std::max(ay_, 1e-4f);
        }
    }
    // pbrt-v4: treated as a perfect specular surface below this roughness.
    bool effectivelySmooth() const { return std::max(ax_, ay_) < 1e-3f; }
    static float roughnessToAlpha(float roughness) { return std::sqrt(std::max(0.0f, roughness)); }

    float D(Vec3 wm) const {
        float t2 = tan2Theta(wm);
        if (std::isinf(t2)) return 0;
        float c4 = sqr(cos2Theta(wm));
        if (c4 < 1e-16f) return 0;
        float s2 = sin2Theta(wm);
        float cos2Phi = s2 > 0 ? wm.x * wm.x / s2 : 1, sin2Phi = s2 > 0 ? wm.y * wm.y / s2 : 0;
        float e = t2 * (cos2Phi / sqr(ax_) + sin2Phi / sqr(ay_));
        return 1 / (kPi * ax_ * ay_ * c4 * sqr(1 + e));
    }
    float lambda(Vec3 w) const {
        float t2 = tan2Theta(w);
        if (std::isinf(t2)) return 0;
        float s2 = sin2Theta(w);
        float cos2Phi = s2 > 0 ? w.x * w.x / s2 : 1, sin2Phi = s2 > 0 ? w.y * w.y / s2 : 0;
        float alpha2 = cos2Phi * sqr(ax_) + sin2Phi * sqr(ay_);
        return (std::sqrt(1 + alpha2 * t2) - 1) / 2;
    }
    float G1(Vec3 w) const { return 1 / (1 + lambda(w)); }
    float G(Vec3 wo, Vec3 wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }
    // Density of visible normals seen from w: G1(w)/|cos w| * D(wm) * |w.wm|.
    float D(Vec3 w, Vec3 wm) const { return G1(w) / absCosTheta(w) * D(wm) * std::fabs(dot(w, wm)); }
    float pdf(Vec3 w, Vec3 wm) const { return D(w, wm); }

    Vec3 sampleVisibleNormal(Vec3 w, Vec2 u) const {
        // Stretch to the hemisphere configuration, sample the projected disk, unstretch.
        Vec3 wh = normalize(Vec3(ax_ * w.x, ay_ * w.y, w.z));
        if (wh.z < 0) wh = -wh;
        Vec3 t1 = wh.z < 0.99999f ? normalize(cross(Vec3(0, 0, 1), wh)) : Vec3(1, 0, 0);
        Vec3 t2 = cross(wh, t1);
        Vec2 p = cosSinTurns(u.y) * std::sqrt(u.x);
        float h = std::sqrt(1 - p.x * p.x);
        p.y = lerp((1 + wh.z) / 2, h, p.y);
        float pz = safeSqrt(1 - p.x * p.x - p.y * p.y);
        Vec3 nh = t1 * p.x + t2 * p.y + wh * pz;
        return normalize(Vec3(ax_ * nh.x, ay_ * nh.y, std::max(1e-6f, nh.z)));
    }

    float alphaX() const { return ax_; }
    float alphaY() const { return ay_; }

private:
    float ax_, ay_;
};

}  // namespace ps
