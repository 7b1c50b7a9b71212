// Which light starts each light subpath (light tracing, BDPT, the Metropolis integrators: thesis
// ch. 10's p(y0)). Any distribution that gives every emitting light a positive probability
// leaves them unbiased; by power alone, most light subpaths of a long corridor or street start
// far from anything the camera sees and are wasted. With the light BVH, the choice follows the
// tree's estimate of what each light sends to the camera's position, mixed with power so that
// lights the camera's position cannot see (a spot light aimed away, a panel facing the far
// wall) still start some subpaths: they may light what the camera sees.
#pragma once
#include <span>
#include <vector>
#include "lights/light.h"
#include "lights/light_sampler.h"
#include "math/vec.h"

namespace ps {

// The share of the bounded lights' probability that stays by power when the choice follows
// the camera's position (bench/README.md, "Many lights": its measurement).
inline constexpr float kEmissionPowerShare = 0.25f;

// Weights (not normalised) by light index. `power` holds each light's power weight; with a
// point-aware `sampler` (null: none) the bounded lights' total is redistributed among them as
// (1 - kEmissionPowerShare) of the sampler's choice at `eye` plus kEmissionPowerShare of power.
// Lights at infinity keep their power weights; so does everything when the sampler at `eye`
// can choose no bounded light.
std::vector<float> emissionChoiceWeights(std::span<const Light* const> lights, std::span<const float> power,
                                         const LightSampler* sampler, Vec3 eye);

}  // namespace ps
