// What a light-choosing tree (lights/light_sampler.h) knows of an emitter or of a group of
// emitters: where they are, how much they emit, and which way. The emitters lie in `bounds`;
// their surface normals (or, for a spot light, the directions it aims at) lie within theta_o
// of w; light leaves each such normal at up to theta_e from it (pi/2 for a diffuse surface).
// pbrt-v4's LightBounds, with the same meaning, so that our "bvh" light sampler chooses as
// pbrt-v4's does.
#pragma once
#include <algorithm>
#include <cmath>
#include "math/bounds3.h"
#include "math/direction_cone.h"

namespace ps {

struct LightBounds {
    Bounds3 bounds;
    Vec3 w{0, 0, 1};
    float phi = 0;         // power, as a weight (0: an empty bound, which unite skips)
    float cosTheta_o = 1;  // the normals' cone
    float cosTheta_e = 0;  // how far from a normal light still leaves
    bool twoSided = false; // emission on both sides of each normal

    LightBounds() = default;
    LightBounds(const Bounds3& b, Vec3 w_, float phi_, float cosTheta_o_, float cosTheta_e_, bool twoSided_)
        : bounds(b), w(normalize(w_)), phi(phi_), cosTheta_o(cosTheta_o_), cosTheta_e(cosTheta_e_),
          twoSided(twoSided_) {}

    Vec3 centroid() const { return bounds.centroid(); }
};

// Bounds holding both a and b; a bound with zero power counts as empty.
LightBounds unite(const LightBounds& a, const LightBounds& b);

// LightBounds in the form the importance is evaluated from: what depends on the bounds alone
// is computed once, since a light-choosing tree evaluates two importances per level for every
// light sample (most of the time of a path tracer's light choice).
class LightImportance {
public:
    LightImportance() = default;
    explicit LightImportance(const LightBounds& b);

    // An estimate of the light these emitters send to point p, whose surface normal is the
    // unit vector n (zero for a point not on a surface): power, times a falloff with the
    // squared distance, times the best cosines the bounds allow at the emitter and at p. It is
    // an upper bound in its orientation terms: zero only where no emitter within the bounds
    // can light p (behind a one-sided surface, outside a spot light's cone), so a sampler that
    // never chooses such a light stays unbiased.
    float at(Vec3 p, Vec3 n) const;

private:
    Vec3 centre_;             // of the box
    float radius_ = 0;        // of the sphere about centre_ that holds the box
    Vec3 w_{0, 0, 1};
    float phi_ = 0;
    float invFalloffFloor_ = 0;  // 1 / the least squared distance the falloff divides by
    float cosTheta_o_ = 1, sinTheta_o_ = 0, cosTheta_e_ = 0;
    bool twoSided_ = false;
    bool allDirections_ = false;  // theta_o = pi: every direction has a normal within the cone
};

// Inline: a tree evaluates both children at once, and the two chains of square roots
// overlap only when the compiler sees both.
namespace light_bounds_detail {

// cos and sin of max(0, a - b) for angles a, b in [0, pi] given by their cosines and sines.
inline float cosSubClamped(float sinA, float cosA, float sinB, float cosB) {
    if (cosA > cosB) return 1;  // a < b
    return cosA * cosB + sinA * sinB;
}
inline float sinSubClamped(float sinA, float cosA, float sinB, float cosB) {
    if (cosA > cosB) return 0;
    return sinA * cosB - cosA * sinB;
}

}  // namespace light_bounds_detail

inline float LightImportance::at(Vec3 p, Vec3 n) const {
    const Vec3 d = p - centre_;
    const float dist2 = lengthSquared(d);

    // theta_w: the angle between the normals' axis and the direction from the bounds to p
    // (any direction will do when p is at their centre: then theta_b below is pi).
    const float invDist = dist2 > 0 ? 1 / std::sqrt(dist2) : 0.0f;
    const Vec3 wi = dist2 > 0 ? d * invDist : w_;

    // theta_b: the half-angle of the cone of directions from p that holds the bounds' bounding
    // sphere (pi from inside the sphere).
    const bool inside = dist2 <= sqr(radius_);
    const float sinTheta_b = inside ? 0.0f : radius_ * invDist;
    const float cosTheta_b = inside ? -1.0f : safeSqrt(1 - sqr(sinTheta_b));

    // theta' = max(0, theta_w - theta_o - theta_b): the smallest angle any emitter's normal
    // can make with the direction to p. Beyond theta_e no light leaves. The test is strict so
    // that an emission range of zero width (a spot light without falloff) still counts the
    // directions inside its cone.
    float cosThetap = 1;
    if (!allDirections_) {
        float cosTheta_w = dot(w_, wi);
        if (twoSided_) cosTheta_w = std::fabs(cosTheta_w);
        const float sinTheta_w = safeSqrt(1 - sqr(cosTheta_w));
        const float cosTheta_x = light_bounds_detail::cosSubClamped(sinTheta_w, cosTheta_w, sinTheta_o_, cosTheta_o_);
        const float sinTheta_x = light_bounds_detail::sinSubClamped(sinTheta_w, cosTheta_w, sinTheta_o_, cosTheta_o_);
        cosThetap = light_bounds_detail::cosSubClamped(sinTheta_x, cosTheta_x, sinTheta_b, cosTheta_b);
        if (cosThetap < cosTheta_e_) return 0;
    }

    // 1 / max(dist2, floor), without a division of its own.
    const float invFalloff2 = dist2 > 0 ? std::min(sqr(invDist), invFalloffFloor_) : invFalloffFloor_;
    float importance = phi_ * cosThetap * invFalloff2;
    // At a surface, the best cosine at p too: theta_i less theta_b, either side of the surface
    // (light may arrive through it).
    if (!(n == Vec3(0, 0, 0))) {
        const float cosTheta_i = absDot(wi, n);
        const float sinTheta_i = safeSqrt(1 - sqr(cosTheta_i));
        importance *= light_bounds_detail::cosSubClamped(sinTheta_i, cosTheta_i, sinTheta_b, cosTheta_b);
    }
    return std::max(importance, 0.0f);
}

}  // namespace ps
