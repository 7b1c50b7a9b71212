// Clarberg's equal-area octahedral mapping between the unit square and the sphere
// (used by pbrt-v4's environment maps): every texel covers the same solid angle 4*pi/N.
#pragma once
#include "math/vec.h"

namespace ps {

Vec3 equalAreaSquareToSphere(Vec2 p);
Vec2 equalAreaSphereToSquare(Vec3 d);

}  // namespace ps
