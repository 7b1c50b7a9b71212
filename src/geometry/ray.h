// Rays and robust spawning of secondary rays off surfaces.
#pragma once
#include <limits>
#include "math/vec.h"

namespace ps {

struct Ray {
    Vec3 o, d;
    float tMax = std::numeric_limits<float>::infinity();
    // The scene time the ray travels at (motion blur): every ray of a path carries the time
    // its camera sample chose, within the shutter interval.
    float time = 0;
};

// Offset a surface point along the geometric normal, to the side of direction w, by an
// amount relative to the point's magnitude; avoids self-intersection without per-shape
// error bounds.
inline Vec3 offsetRayOrigin(Vec3 p, Vec3 ng, Vec3 w) {
    float scale = 1.0f + std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
    Vec3 off = ng * (2e-5f * scale);
    return dot(w, ng) < 0 ? p - off : p + off;
}

inline Ray spawnRay(Vec3 p, Vec3 ng, Vec3 d, float time) {
    return Ray{offsetRayOrigin(p, ng, d), d, std::numeric_limits<float>::infinity(), time};
}

// A shadow ray from p (on a surface with normal ng) to target; shortened so it does not
// hit the surface the target lies on.
inline Ray spawnRayTo(Vec3 p, Vec3 ng, Vec3 target, float time) {
    Vec3 o = offsetRayOrigin(p, ng, target - p);
    Vec3 d = target - o;
    return Ray{o, d, 1.0f - 1e-4f, time};
}

}  // namespace ps
