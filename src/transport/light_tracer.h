// Light (particle) tracing (thesis §4.A / ch. 10's t = 1 strategies alone): one light
// subpath per pixel sample, each vertex connected to a sampled lens point and splatted
// onto the film, with the adjoint BSDF of importance transport (thesis ch. 5). Normalised
// as pbrt-v4's light path integrator: the image is the splat sum over the number of
// light paths, times the film's pixel count.
#pragma once
#include "transport/bdpt.h"

namespace ps {

class LightTracer final : public Integrator {
public:
    LightTracer(const Scene& scene, int maxDepth) : bdpt_(scene, maxDepth, MisHeuristic::Uniform) {}
    Spectrum Li(const Ray& ray, SampleContext& ctx) const override;
    bool splats() const override { return true; }
    bool supportsSpectral() const override { return true; }

private:
    // The (s, t) = (1, 1) strategy: the light point itself seen through the lens.
    void splatEmitter(const PathVertex& v, SampleContext& ctx, const MediaSample* media) const;
    // The t = 0 paths that the lens connections miss (light_tracer.cpp).
    void splatLensHits(const PathVertex* light, const LensHits& lens, SampleContext& ctx) const;
    BDPTIntegrator bdpt_;  // its connection code; light tracing uses no MIS
};

}  // namespace ps
