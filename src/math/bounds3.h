// Axis-aligned boxes in 3D: the spatial part of a light's bounds (lights/light_bounds.h).
// Embree keeps the boxes of the geometry; this type is for what we reason about ourselves.
#pragma once
#include <cmath>
#include <limits>
#include "math/vec.h"

namespace ps {

struct Bounds3 {
    // Empty by default: lo above hi, so that the first point or box expanded in is the box.
    Vec3 lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
            std::numeric_limits<float>::infinity()};
    Vec3 hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
            -std::numeric_limits<float>::infinity()};

    Bounds3() = default;
    explicit Bounds3(Vec3 p) : lo(p), hi(p) {}
    Bounds3(Vec3 a, Vec3 b) : lo(vmin(a, b)), hi(vmax(a, b)) {}

    bool isEmpty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    void expand(Vec3 p) { lo = vmin(lo, p); hi = vmax(hi, p); }
    void expand(const Bounds3& b) { lo = vmin(lo, b.lo); hi = vmax(hi, b.hi); }
    Vec3 centroid() const { return (lo + hi) * 0.5f; }
    Vec3 diagonal() const { return hi - lo; }
    float surfaceArea() const {
        Vec3 d = diagonal();
        return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
    // p's position in the box per axis, 0 at lo and 1 at hi (0 along an axis without extent).
    Vec3 offset(Vec3 p) const {
        Vec3 o = p - lo, d = diagonal();
        return {d.x > 0 ? o.x / d.x : 0.0f, d.y > 0 ? o.y / d.y : 0.0f, d.z > 0 ? o.z / d.z : 0.0f};
    }
};

inline Bounds3 unite(Bounds3 a, const Bounds3& b) {
    a.expand(b);
    return a;
}

}  // namespace ps
