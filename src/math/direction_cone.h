// A set of directions bounded by a cone: every direction within angle theta of the unit axis
// w. Light bounds (lights/light_bounds.h) use it for the normals of an emitter, the directions
// a spot light aims at, and their unions up a tree of lights.
#pragma once
#include "math/vec.h"

namespace ps {

struct DirectionCone {
    Vec3 w{0, 0, 1};
    float cosTheta = -1;  // -1: the entire sphere, whatever w

    DirectionCone() = default;
    DirectionCone(Vec3 axis, float cosTheta_) : w(normalize(axis)), cosTheta(cosTheta_) {}
    static DirectionCone entireSphere() { return {}; }
    bool isEntireSphere() const { return cosTheta <= -1; }
};

// The angle between unit vectors a and b, accurate also when they are nearly parallel or
// opposite (where acos of their dot product loses most of its digits).
float angleBetween(Vec3 a, Vec3 b);

// A cone holding both a and b (the smallest one whose axis lies in their common plane).
DirectionCone unite(const DirectionCone& a, const DirectionCone& b);

}  // namespace ps
