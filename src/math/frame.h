// Orthonormal frames: shading computations happen in a local frame with the normal on +z.
#pragma once
#include <optional>
#include "math/vec.h"

namespace ps {

// Branchless orthonormal basis around a unit vector (Duff et al. 2017).
inline void coordinateSystem(Vec3 n, Vec3& s, Vec3& t) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    s = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    t = Vec3(b, sign + n.y * n.y * a, -n.y);
}

struct Frame {
    Vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};
    Frame() = default;
    Frame(Vec3 s_, Vec3 t_, Vec3 n_) : s(s_), t(t_), n(n_) {}
    static Frame fromNormal(Vec3 n) {
        Frame f;
        f.n = n;
        coordinateSystem(n, f.s, f.t);
        return f;
    }
    // Frame with normal n whose first axis follows the tangent dpdu (Gram-Schmidt).
    static Frame fromNormalTangent(Vec3 n, Vec3 dpdu) {
        if (std::optional<Vec3> s = unitTangent(n, dpdu)) return Frame(*s, cross(n, *s), n);
        return fromNormal(n);  // zero, parallel to n, or non-finite: any tangent will do
    }
    // fromNormalTangent's first axis: dpdu made orthogonal to n and unit, or nothing where
    // dpdu is zero, parallel to n or not finite.
    static std::optional<Vec3> unitTangent(Vec3 n, Vec3 dpdu) {
        Vec3 s = dpdu - n * dot(n, dpdu);
        float l2 = lengthSquared(s);
        if (!(l2 > 1e-10f * lengthSquared(dpdu)) || !std::isfinite(l2)) return std::nullopt;
        return s / std::sqrt(l2);
    }
    Vec3 toLocal(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 toWorld(Vec3 v) const { return s * v.x + t * v.y + n * v.z; }
};

// Local shading-frame trigonometry (z is the normal).
inline float cosTheta(Vec3 w) { return w.z; }
inline float absCosTheta(Vec3 w) { return std::fabs(w.z); }
inline float cos2Theta(Vec3 w) { return w.z * w.z; }
inline float sin2Theta(Vec3 w) { return std::max(0.0f, 1.0f - w.z * w.z); }
inline float tan2Theta(Vec3 w) { return sin2Theta(w) / cos2Theta(w); }
inline bool sameHemisphere(Vec3 a, Vec3 b) { return a.z * b.z > 0; }

}  // namespace ps
