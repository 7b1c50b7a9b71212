// Russian roulette on visibility tests (thesis §10.3.4, "efficiency-optimized Russian
// roulette"): a connection whose unoccluded contribution C is small next to a threshold tau
// traces its shadow ray with probability q = min(1, C / tau) and, if it does, counts C / q.
// Unbiased for any tau (E = q C / q); the efficiency 1/(V T) is best where tau grows with the
// square root of the per-sample variance over the shadow ray's share of the time (the
// variance added, C^2 (1/q - 1), against the time saved, (1 - q) t_ray: d/dq = 0 gives q
// proportional to C). The renderer sets tau from the image's mean between passes
// (docs/robustness.md); tau = 0 turns it off.
#pragma once
#include <algorithm>
#include <cstdint>

#include "math/spectrum.h"
#include "mc/rng.h"
#include "transport/spectral_film.h"

namespace ps {

struct ShadowRoulette {
    float tau = 0;     // the threshold, in the film's units per sample (0: off)
    uint64_t key = 0;  // this camera sample's (render seed, pixel, sample index)
    // Spectral mode: the sample's wavelengths and the film's sensor, through which C is
    // compared with tau in the film's units (values at wavelengths have other magnitudes).
    const SpectralFilm* sensor = nullptr;
    const SampledWavelengths* lambda = nullptr;

    bool active() const { return tau > 0; }
    // Whether to trace the visibility test of connection `slot` (distinct per connection of
    // one sample) whose unoccluded contribution is C; *scale is 1 / q when it is traced.
    bool trace(const Spectrum& C, uint64_t slot, float* scale) const {
        *scale = 1;
        if (!(tau > 0)) return true;
        // The largest channel of the film's colour: a connection bright in any is traced.
        const float c = sensor && lambda ? sensor->toRendering(C, *lambda).maxComponent() : C.maxComponent();
        if (!(c < tau)) return true;
        const float q = std::max(c / tau, 1e-6f);  // never a weight above 1e6
        const float u = float(mix64(hashCombine(key, slot)) >> 40) * 0x1p-24f;
        if (u >= q) return false;
        *scale = 1 / q;
        return true;
    }
};

}  // namespace ps
