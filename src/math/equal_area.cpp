#include "math/equal_area.h"

namespace ps {

// Fold the square onto the octahedron: the distance from the centre's diamond gives the
// polar radius r (z = +-(1 - r^2) keeps area), the position along the diamond's edge the azimuth.
Vec3 equalAreaSquareToSphere(Vec2 p) {
    float u = 2 * p.x - 1, v = 2 * p.y - 1;
    float up = std::fabs(u), vp = std::fabs(v);
    float signedDist = 1 - (up + vp);
    float d = std::fabs(signedDist);
    float r = 1 - d;
    float phi = (r == 0 ? 1 : (vp - up) / r + 1) * (kPi / 4);
    float z = std::copysign(1 - r * r, signedDist);
    float cosPhi = std::copysign(std::cos(phi), u);
    float sinPhi = std::copysign(std::sin(phi), v);
    float s = r * safeSqrt(2 - r * r);
    return {cosPhi * s, sinPhi * s, z};
}

Vec2 equalAreaSphereToSquare(Vec3 d) {
    float x = std::fabs(d.x), y = std::fabs(d.y), z = std::fabs(d.z);
    float r = safeSqrt(1 - z);
    float a = std::max(x, y), b = std::min(x, y);
    b = a == 0 ? 0 : b / a;
    float phi = std::atan(b) * (2 / kPi);
    if (x < y) phi = 1 - phi;
    float v = phi * r;
    float u = r - v;
    if (d.z < 0) {
        std::swap(u, v);
        u = 1 - u;
        v = 1 - v;
    }
    u = std::copysign(u, d.x);
    v = std::copysign(v, d.y);
    return {clampf((u + 1) * 0.5f, 0, 1), clampf((v + 1) * 0.5f, 0, 1)};
}

Vec2 wrapEqualAreaSquare(Vec2 p) {
    // Crossing the left or right edge lands mirrored about the horizontal midline, crossing the
    // top or bottom edge mirrored about the vertical one; a corner crossing does both.
    if (p.x < 0) {
        p = {-p.x, 1 - p.y};
    } else if (p.x > 1) {
        p = {2 - p.x, 1 - p.y};
    }
    if (p.y < 0) {
        p = {1 - p.x, -p.y};
    } else if (p.y > 1) {
        p = {1 - p.x, 2 - p.y};
    }
    return p;
}

}  // namespace ps
