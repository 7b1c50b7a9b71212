// What an integrator knows about a ray's hit point.
#pragma once
#include "math/frame.h"
#include "math/vec.h"

namespace ps {

class Material;
class Light;

struct SurfaceInteraction {
    Vec3 p;
    float t = 0;
    Vec3 ng;        // geometric normal, oriented by pbrt's rules (winding/N/ReverseOrientation)
    Vec3 ns;        // shading normal, in the hemisphere of ng
    Vec3 dpdu;      // shading tangent along u
    Vec2 uv;
    Vec3 wo;        // towards the ray origin
    const Material* material = nullptr;
    const Light* areaLight = nullptr;  // the emitter at this point, if any

    Frame shadingFrame() const { return Frame::fromNormalTangent(ns, dpdu); }
};

}  // namespace ps
