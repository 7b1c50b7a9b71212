// Ken Perlin's improved gradient noise (2002) with the permutation and gradient choice pbrt-v4
// uses (util/noise.cpp: Noise, DNoise), so that its "cloud" medium has pbrt-v4's density field
// value for value: the same scene file then gives the same image. Written from the published
// algorithm; the 256-entry table is Perlin's reference permutation.
#pragma once
#include "math/vec.h"

namespace ps {

// Noise at p, in about [-1, 1], zero at every integer lattice point. Coordinates are first
// reduced modulo 2^30 (pbrt-v4: the cell deltas stay representable for huge inputs).
float perlinNoise(Vec3 p);

// pbrt-v4's DNoise: a forward difference of perlinNoise with step 0.01 along each axis (not
// the analytic gradient), which the cloud's wispiness displaces its lookups by.
Vec3 perlinNoiseDifference(Vec3 p);

// A bound on |perlinNoise| everywhere: each corner's gradient term is +-a +-b with |a|, |b| <= 1
// and the fade-weighted trilinear blend is a convex combination of the eight terms.
inline constexpr float kPerlinNoiseBound = 2.0f;

}  // namespace ps
