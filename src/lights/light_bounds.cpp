#include "lights/light_bounds.h"

#include <algorithm>
#include <cmath>

namespace ps {

namespace {

// cos and sin of max(0, a - b) for angles a, b in [0, pi] given by their cosines and sines.
float cosSubClamped(float sinA, float cosA, float sinB, float cosB) {
    if (cosA > cosB) return 1;  // a < b
    return cosA * cosB + sinA * sinB;
}
float sinSubClamped(float sinA, float cosA, float sinB, float cosB) {
    if (cosA > cosB) return 0;
    return sinA * cosB - cosA * sinB;
}

}  // namespace

LightBounds unite(const LightBounds& a, const LightBounds& b) {
    if (a.phi == 0) return b;
    if (b.phi == 0) return a;
    DirectionCone cone = unite(DirectionCone(a.w, a.cosTheta_o), DirectionCone(b.w, b.cosTheta_o));
    // The widest emission of the two (cosines fall as angles grow).
    return LightBounds(unite(a.bounds, b.bounds), cone.w, a.phi + b.phi, cone.cosTheta,
                       std::min(a.cosTheta_e, b.cosTheta_e), a.twoSided || b.twoSided);
}

float LightBounds::importance(Vec3 p, Vec3 n) const {
    const Vec3 pc = bounds.centroid();
    const Vec3 d = p - pc;
    const float dist2 = lengthSquared(d);
    // pbrt-v4's clamp of the falloff near the emitters (it compares the squared distance with
    // half the diagonal's length, not its square; kept, so that we choose as pbrt-v4 does), and
    // a floor where p is a point light's own position.
    const float falloff2 = std::max({dist2, length(bounds.diagonal()) / 2, 1e-20f});

    // theta_w: the angle between the normals' axis and the direction from the bounds to p
    // (any direction will do when p is at their centre: then theta_b below is pi).
    const Vec3 wi = dist2 > 0 ? d / std::sqrt(dist2) : w;
    float cosTheta_w = dot(w, wi);
    if (twoSided) cosTheta_w = std::fabs(cosTheta_w);
    const float sinTheta_w = safeSqrt(1 - sqr(cosTheta_w));

    // theta_b: the half-angle of the cone of directions from p that holds the bounds' bounding
    // sphere (pi from inside the sphere).
    const float r2 = lengthSquared(bounds.hi - pc);
    const float cosTheta_b = dist2 <= r2 ? -1.0f : safeSqrt(1 - r2 / dist2);
    const float sinTheta_b = safeSqrt(1 - sqr(cosTheta_b));

    // theta' = max(0, theta_w - theta_o - theta_b): the smallest angle any emitter's normal
    // can make with the direction to p. Beyond theta_e no light leaves. The test is strict so
    // that an emission range of zero width (a spot light without falloff) still counts the
    // directions inside its cone.
    const float sinTheta_o = safeSqrt(1 - sqr(cosTheta_o));
    const float cosTheta_x = cosSubClamped(sinTheta_w, cosTheta_w, sinTheta_o, cosTheta_o);
    const float sinTheta_x = sinSubClamped(sinTheta_w, cosTheta_w, sinTheta_o, cosTheta_o);
    const float cosThetap = cosSubClamped(sinTheta_x, cosTheta_x, sinTheta_b, cosTheta_b);
    if (cosThetap < cosTheta_e) return 0;

    float importance = phi * cosThetap / falloff2;
    // At a surface, the best cosine at p too: theta_i less theta_b, either side of the surface
    // (light may arrive through it).
    if (!(n == Vec3(0, 0, 0))) {
        const float cosTheta_i = absDot(wi, n) / length(n);
        const float sinTheta_i = safeSqrt(1 - sqr(cosTheta_i));
        importance *= cosSubClamped(sinTheta_i, cosTheta_i, sinTheta_b, cosTheta_b);
    }
    return std::max(importance, 0.0f);
}

}  // namespace ps
