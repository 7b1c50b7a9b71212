// pbrt-v4's Perlin noise and its sums over octaves, for the procedural textures. The noise
// is a fixed function of the point (gradient noise on the integer lattice, gradients chosen
// through a fixed permutation table), so textures built on it match pbrt-v4's images point
// for point. It is 0 at every lattice point, repeats with period 256 along each axis, and
// stays within about [-1, 1] (measured maximum |noise| just above 1).
#pragma once
#include "math/vec.h"

namespace ps {

// Each octave multiplies the frequency by this (not exactly 2, so the octaves' lattices do
// not line up).
constexpr float kOctaveLacunarity = 1.99f;

// pbrt-v4's Noise(x, y, z); the 2-D form fixes z = 0.5, as pbrt-v4's does. 0 for non-finite input.
float perlinNoise(float x, float y = 0.5f, float z = 0.5f);
inline float perlinNoise(Vec3 p) { return perlinNoise(p.x, p.y, p.z); }

// A bound on |perlinNoise| everywhere, provable rather than measured: each corner's term is
// +-a +-b with |a|, |b| <= 1 and the faded trilinear blend is a convex combination of the eight
// (the cloud medium's majorant grid relies on it).
constexpr float kPerlinNoiseBound = 2.0f;

// pbrt-v4's DNoise: forward differences of the noise with step 0.01 along each axis (not the
// analytic gradient); the cloud medium displaces its lookups by it.
Vec3 perlinNoiseDifference(Vec3 p);

// Fractional Brownian motion: sum over i < octaves of omega^i noise(1.99^i p). pbrt-v4's FBm
// with a zero filter footprint (all octaves, none faded out).
float fbm(Vec3 p, float omega, int octaves);
// Turbulence: sum over i < octaves of omega^i |noise(1.99^i p)|, plus 0.2 omega^octaves for the
// octave beyond, as pbrt-v4's Turbulence with a zero filter footprint.
float turbulence(Vec3 p, float omega, int octaves);

}  // namespace ps
