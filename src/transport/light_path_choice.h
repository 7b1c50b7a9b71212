// `--light-paths auto`: BDPT's light path share chosen by a pilot (BDPTIntegrator::
// setLightPathShare). A share F mixes whole BDPT samples (F) with the path tracer's (1 - F);
// both are unbiased wherever both sample a path, so the mix's variance and cost per sample
// are both linear in F and their product, the inverse of the efficiency 1/(V T) (thesis
// §2.5.1), is smallest at an end: F = 1 or the least F that still samples what only light
// subpaths reach. The pilot renders a few samples per pixel of each end, timed, and keeps
// the end whose efficiency is higher.
//
// The pilot's samples are left out of the image. Any fixed weights would keep it unbiased
// although the choice depends on them, but a few samples per pixel of a separate set are
// several times noisier than as many more of the render's stratified set: on the Cornell box,
// 2 + 2 of them beside 32 made the image 1.2x noisier than the 32 alone (bench/README.md).
#pragma once
#include <cstdint>

#include "transport/renderer.h"

namespace ps {

class BDPTIntegrator;
class Scene;

struct LightPathChoice {
    float share = 1;
    // Each pilot's mean relative pixel variance times its seconds (1 / efficiency). Timed:
    // BDPT's cost per ray is not the path tracer's, so a ray count would misjudge it; the
    // choice may then differ between machines where the two are close (the first process
    // decides for all).
    double pathVarianceTime = 0, bdptVarianceTime = 0;
    double seconds = 0;  // both pilots' time, which a time-budgeted render takes from its budget
};

// The share used where path tracing wins: 0 where every path is the path tracer's too, else
// (delta lights with specular surfaces or a lens) a floor for the paths only light subpaths
// reach.
float lightOnlyFloor(const Scene& scene);

// Renders the pilots with `bdpt` at shares 0 and 1 (independent samples, `options`' threads
// and seed), then leaves bdpt at the chosen share. Collective: every process calls it.
LightPathChoice chooseLightPathShare(const Scene& scene, BDPTIntegrator& bdpt, const RenderOptions& options);

}  // namespace ps
