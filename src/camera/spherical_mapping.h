// The spherical camera's film-to-direction maps (pbrt-v4's semantics): the whole sphere of
// directions around the camera on one film, either equal-area (every pixel of a square film
// sees the same solid angle) or equirectangular (latitude-longitude).
#pragma once
#include "math/vec.h"

namespace ps {

enum class SphericalMapping { EqualArea, Equirectangular };

// The camera-space unit direction seen at film point uv = pFilm / resolution (u to the right,
// v down, [0,1]^2 on the film; the filter may reach slightly beyond).
//  * Equal-area: the octahedral equal-area square with its y and z swapped, so the film
//    centre looks up (+y), the four corners down (-y), right-middle along +x, bottom-middle
//    forward (+z) and top-middle backward (-z).
//  * Equirectangular: theta = pi v from +y (the top row looks up, the bottom row down), phi =
//    2 pi u from +x towards +z: the left edge looks along +x, a quarter across forward (+z),
//    the middle along -x.
Vec3 sphericalCameraDirection(SphericalMapping m, Vec2 uv);

}  // namespace ps
