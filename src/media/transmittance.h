// Transmittance between two points of a scene with media (pbrt-v4's volpath SampleLd): the
// segment is followed through `interface` shapes, changing medium at each, and estimated by
// ratio tracking (Novak et al. 2014) in each medium, with the spectral-MIS ratios of the
// hero channel's tracking. Shared by every integrator that connects vertices in media.
#pragma once
#include "geometry/ray.h"
#include "mc/rng.h"
#include "media/medium.h"

namespace ps {

class Scene;

// The ratio-tracking estimate T (already divided by the hero's tracking density), and the
// unidirectional (rU) and light (rL) path-density ratios it contributes; pbrt-v4 divides
// T by the channel mean of rU + rL for a shadow ray. Zero T: blocked by a surface that
// is not `interface`, or the walk was ended by Russian roulette.
struct TransmittanceEstimate {
    Spectrum T{1.0f}, rU{1.0f}, rL{1.0f};
    int rays = 0;
};

// From p (on a surface of geometric normal ng, or ng = 0 in a medium), in `medium`, to target.
TransmittanceEstimate transmittance(const Scene& scene, Vec3 p, Vec3 ng, const Medium* medium, Vec3 target, float time,
                                    const SampledWavelengths* lambda, int hero, bool spectral, Rng& rng);

}  // namespace ps
