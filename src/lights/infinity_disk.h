// Rays from lights at infinity (thesis §10.2, pbrt's "disk at infinity"): the emitted
// ray for direction w starts on a disk of the scene's bounding-sphere radius, centred
// on the sphere's tangent plane at the light's side and facing along -w, so every ray
// that can reach the scene from that direction is covered with uniform area density.
#pragma once
#include "geometry/ray.h"
#include "math/frame.h"
#include "math/warp.h"

namespace ps {

// wToLight: unit direction towards the light; the ray travels along -wToLight.
inline Ray rayFromInfinityDisk(Vec3 wToLight, Vec3 sceneCenter, float sceneRadius, Vec2 u) {
    Frame f = Frame::fromNormal(wToLight);
    Vec2 d = sampleConcentricDisk(u) * sceneRadius;
    Vec3 o = sceneCenter + wToLight * sceneRadius + f.s * d.x + f.t * d.y;
    return Ray{o, -wToLight};
}

inline float infinityDiskPdf(float sceneRadius) { return 1 / (kPi * sceneRadius * sceneRadius); }

}  // namespace ps
