// Sampling a ray's distances by its medium's majorant (pbrt-v4's SampleT_maj): the points
// of a homogeneous Poisson process of density sigma_maj[hero] along the ray, at each of which
// `event(p, props, sigmaMaj, Tmaj)` decides (delta tracking: absorb, scatter or pass through
// a null collision; ratio tracking: weigh by sigma_n / sigma_maj). Tmaj is the majorant's
// transmittance since the previous event. Returns the majorant transmittance from the last
// event to the end of the ray, or 1 when an event stopped the walk. The ray is a copy: an
// event may move the caller's ray (a scattering).
#pragma once
#include "geometry/ray.h"
#include "mc/rng.h"
#include "media/medium.h"

namespace ps {

template <typename Event>
Spectrum sampleMajorant(const Medium& medium, Ray ray, float tMax, float u, Rng& rng,
                        const SampledWavelengths* lambda, int hero, Event&& event) {
    const float len = length(ray.d);
    if (!(len > 0)) return Spectrum(1.0f);
    const Vec3 d = ray.d / len;
    MajorantSegment seg;
    // Distances, not ray parameters: shadow rays have unnormalised directions.
    if (!medium.segment(ray.o, d, tMax * len, lambda, &seg)) return Spectrum(1.0f);
    const float sm = seg.sigmaMaj[hero];
    if (!(sm > 0)) return expNeg(seg.sigmaMaj * std::max(0.0f, seg.t1 - seg.t0));
    float t = seg.t0;
    while (true) {
        const float dt = -std::log(1 - u) / sm;
        u = rng.uniform();
        if (!(t + dt < seg.t1)) return expNeg(seg.sigmaMaj * std::max(0.0f, seg.t1 - t));
        t += dt;
        const Vec3 p = ray.o + d * t;
        if (!event(p, medium.at(p, lambda), seg.sigmaMaj, expNeg(seg.sigmaMaj * dt))) return Spectrum(1.0f);
    }
}

}  // namespace ps
