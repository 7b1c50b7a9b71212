// Clarberg's equal-area octahedral mapping between the unit square and the sphere
// (used by pbrt-v4's environment maps): every texel covers the same solid angle 4*pi/N.
#pragma once
#include "math/vec.h"

namespace ps {

Vec3 equalAreaSquareToSphere(Vec2 p);
Vec2 equalAreaSphereToSquare(Vec3 d);
// A point up to one square beyond an edge, folded back onto the square: the octahedral layout
// continues across each edge mirrored about that edge's midpoint (pbrt-v4's semantics).
Vec2 wrapEqualAreaSquare(Vec2 p);

}  // namespace ps
