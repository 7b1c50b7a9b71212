// What a light-choosing tree (lights/light_sampler.h) knows of an emitter or of a group of
// emitters: where they are, how much they emit, and which way. The emitters lie in `bounds`;
// their surface normals (or, for a spot light, the directions it aims at) lie within theta_o
// of w; light leaves each such normal at up to theta_e from it (pi/2 for a diffuse surface).
// pbrt-v4's LightBounds, with the same meaning, so that our "bvh" light sampler chooses as
// pbrt-v4's does.
#pragma once
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

    // An estimate of the light these emitters send to point p, whose surface normal is n (zero
    // for a point not on a surface): power, times a falloff with the squared distance, times
    // the best cosines the bounds allow at the emitter and at p. It is an upper bound in its
    // orientation terms: zero only where no emitter within the bounds can light p (behind a
    // one-sided surface, outside a spot light's cone), so a sampler that never chooses such
    // a light stays unbiased.
    float importance(Vec3 p, Vec3 n) const;
};

// Bounds holding both a and b; a bound with zero power counts as empty.
LightBounds unite(const LightBounds& a, const LightBounds& b);

}  // namespace ps
