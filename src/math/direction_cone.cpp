#include "math/direction_cone.h"

#include <algorithm>
#include <cmath>

namespace ps {

float angleBetween(Vec3 a, Vec3 b) {
    // Half the chord between the two points on the unit sphere is the sine of half the angle.
    if (dot(a, b) < 0) return kPi - 2 * std::asin(std::min(1.0f, length(a + b) / 2));
    return 2 * std::asin(std::min(1.0f, length(b - a) / 2));
}

DirectionCone unite(const DirectionCone& a, const DirectionCone& b) {
    if (a.isEntireSphere() || b.isEntireSphere()) return DirectionCone::entireSphere();
    const float thetaA = safeAcos(a.cosTheta), thetaB = safeAcos(b.cosTheta);
    const float thetaD = angleBetween(a.w, b.w);
    // One cone inside the other: the bigger one already holds both.
    if (std::min(thetaD + thetaB, kPi) <= thetaA) return a;
    if (std::min(thetaD + thetaA, kPi) <= thetaB) return b;
    // Otherwise the new cone spans from a's far edge to b's far edge along the great circle
    // through both axes: its half-angle is half that span, its axis the span's middle.
    const float thetaO = (thetaA + thetaD + thetaB) / 2;
    if (thetaO >= kPi) return DirectionCone::entireSphere();
    Vec3 toB = b.w - a.w * dot(a.w, b.w);  // in the common plane, perpendicular to a.w
    float l2 = lengthSquared(toB);
    if (!(l2 > 0)) return DirectionCone::entireSphere();  // opposite axes: no single plane
    const float thetaR = thetaO - thetaA;                 // how far to turn a.w towards b.w
    Vec3 w = a.w * std::cos(thetaR) + toB * (std::sin(thetaR) / std::sqrt(l2));
    return DirectionCone(w, std::cos(thetaO));
}

}  // namespace ps
