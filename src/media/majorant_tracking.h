// Sampling a ray's distances by its medium's majorant (pbrt-v4's SampleT_maj): the points
// of a homogeneous Poisson process of density sigma_maj[hero] along the ray, at each of which
// `event(p, props, sigmaMaj, Tmaj)` decides (delta tracking: absorb, scatter or pass through
// a null collision; ratio tracking: weigh by sigma_n / sigma_maj). Tmaj is the majorant's
// transmittance since the previous event. Returns the majorant transmittance from the last
// event to the end of the ray, or 1 when an event stopped the walk. The ray is a copy: an
// event may move the caller's ray (a scattering). The majorant may change from segment to
// segment (a MajorantGrid's cells); Tmaj then spans the segments since the last event.
#pragma once
#include "geometry/ray.h"
#include "mc/rng.h"
#include "media/majorant_grid.h"
#include "media/medium_lookup.h"

namespace ps {

template <typename Event>
Spectrum sampleMajorant(const Medium& medium, Ray ray, float tMax, float u, Rng& rng,
                        const SampledWavelengths* lambda, int hero, Event&& event) {
    const float len = length(ray.d);
    if (!(len > 0)) return Spectrum(1.0f);
    const Vec3 d = ray.d / len;
    const MediumLookup lookup(medium, lambda);
    // Distances, not ray parameters: shadow rays have unnormalised directions.
    MajorantIterator segments = lookup.majorants(ray.o, d, tMax * len);
    // The majorant's optical depth since the last event: one exp per event, not one per cell.
    Spectrum tau(0.0f);
    MajorantSegment seg;
    while (segments.next(&seg)) {
        const float sm = seg.sigmaMaj[hero];
        if (!(sm > 0)) {  // an empty cell (or a hero channel the medium leaves alone)
            tau += seg.sigmaMaj * std::max(0.0f, seg.t1 - seg.t0);
            continue;
        }
        float t = seg.t0;
        while (true) {
            const float dt = -std::log(1 - u) / sm;
            u = rng.uniform();
            if (!(t + dt < seg.t1)) {
                // Past the segment: the flight goes on in the next one with a fresh u, as
                // pbrt-v4's SampleT_maj (memorylessness makes the restart exact).
                tau += seg.sigmaMaj * std::max(0.0f, seg.t1 - t);
                break;
            }
            t += dt;
            tau += seg.sigmaMaj * dt;
            const Vec3 p = ray.o + d * t;
            if (!event(p, lookup.at(p), seg.sigmaMaj, expNeg(tau))) return Spectrum(1.0f);
            tau = Spectrum(0.0f);
        }
    }
    return expNeg(tau);
}

}  // namespace ps
