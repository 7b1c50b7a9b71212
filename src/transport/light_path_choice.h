// `--light-paths auto`: BDPT's light path share chosen by a pilot (BDPTIntegrator::
// setLightPathShare). A share F mixes whole BDPT samples (F) with the path tracer's (1 - F);
// both are unbiased wherever both sample a path, so the mix's variance and cost per sample
// are both linear in F and their product, the inverse of the efficiency 1/(V T) (thesis
// §2.5.1), is smallest at an end: F = 1 or the least F that still samples what only light
// subpaths reach. The pilot renders a few samples per pixel of each and keeps the end whose
// efficiency is higher.
#pragma once
#include <cstdint>

namespace ps {

class BDPTIntegrator;
class Scene;

struct LightPathChoice {
    float share = 1;
    int pilotSpp = 0;
    // Each pilot's mean relative pixel variance (over the squared luminance + 0.01, as the
    // benches' relMSE) times its seconds (1 / efficiency). Timed: BDPT's cost
    // per ray is not the path tracer's, so a count would misjudge it; the choice may then
    // differ between machines where the two are close (the first process decides for all).
    double pathVarianceTime = 0, bdptVarianceTime = 0;
    float floor = 0;  // lightOnlyFloor: the share where path tracing wins
};

// The share used where path tracing wins: 0 without delta lights (every path is the path
// tracer's too), else a floor for the paths only light subpaths reach.
float lightOnlyFloor(const Scene& scene);

// Renders the pilot with `bdpt` at shares 0 and 1 (independent samples, `seed`), then leaves
// bdpt at the chosen share. Collective: every process calls it.
LightPathChoice chooseLightPathShare(const Scene& scene, BDPTIntegrator& bdpt, int threads, uint64_t seed);

}  // namespace ps
