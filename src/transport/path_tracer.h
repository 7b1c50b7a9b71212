// Unidirectional path tracing with next-event estimation and BSDF sampling combined by
// multiple importance sampling (thesis ch. 9; the power heuristic unless --mis says
// otherwise), Russian roulette after the second bounce (thesis §2.5.3.2 / pbrt-v4's rule),
// maxdepth = number of scattering events.
#pragma once
#include "mc/mis.h"
#include "mc/rng.h"
#include "transport/integrator.h"

namespace ps {

class PathTracer final : public Integrator {
public:
    // mis: how light and BSDF sampling are weighted (thesis ch. 9; mc/mis.h). Scenes with
    // media always use volpath's spectral balance weights (createIntegrator refuses others).
    // lightSamples: light samples per vertex (--light-samples; docs/strategy-figures.md),
    // splitting next-event estimation (thesis §2.5.3.2); each counts 1 / N, and the MIS
    // weights see the light technique as N samples (thesis §9.2's multi-sample model).
    PathTracer(const Scene& scene, int maxDepth, MisWeighting mis = {}, int lightSamples = 1)
        : scene_(scene), maxDepth_(maxDepth), mis_(mis), defaultMis_(mis.isDefault()), lightSamples_(lightSamples),
          lightCount_(float(lightSamples)) {}
    Spectrum Li(const Ray& ray, SampleContext& ctx) const override;
    bool supportsSpectral() const override { return true; }
    // Light sampling (next-event estimation) and BSDF sampling (emitters the path finds, the
    // camera ray's and specular bounces' included); none in media (volpath's are spectral MIS).
    std::vector<RenderTechnique> techniques() const override;
    static constexpr int kLightTechnique = 0, kBsdfTechnique = 1;

private:
    // A scattering vertex of a path in media: on a surface (bxdf, si) or in a medium (the
    // phase function of `medium`).
    struct VolVertex {
        Vec3 p, ng, wo, woLocal;
        Frame frame;
        const BxDF* bxdf = nullptr;
        const SurfaceInteraction* si = nullptr;
        const Medium* medium = nullptr;  // the medium the vertex is in (surfaces: the arriving ray's)
        float time = 0;
    };
    // pbrt-v4's volpath, for scenes with media (volpath.cpp).
    Spectrum estimateInMedia(const Ray& ray, Sampler& sampler, ScratchBuffer& scratch, PathStats& stats,
                             SampledWavelengths* lambda) const;
    Spectrum sampleDirectInMedia(const VolVertex& v, const Spectrum& beta, const Spectrum& rPath, int hero, Sampler& sampler,
                                 Rng& rng, const SampledWavelengths* lambda, PathStats& stats) const;
    // The estimator, instantiated per concrete sampler so its calls inline on the hot path.
    // Split: N light samples (--light-samples) and each technique's part reported to
    // ctx.tally (--stats); the plain instance does no such work.
    template <bool Split, typename S>
    Spectrum estimate(const Ray& ray, S& sampler, SampleContext& ctx) const;
    // Direct lighting at a surface by one light sample (uLight picks the light, u the point on
    // it), MIS-weighted against BSDF sampling with the light technique's sample count
    // (lightCount_); the caller divides by it. beta: the path's throughput, which the caller
    // multiplies in; with `roulette` its shadow ray (slot: the vertex and sample) may be left out.
    Spectrum sampleDirect(const SurfaceInteraction& si, const Frame& frame, const BxDF& bxdf, Vec3 woLocal,
                          float uLight, Vec2 u, float time, const SampledWavelengths* lambda, PathStats& stats,
                          const Spectrum& beta, const ShadowRoulette& roulette, uint64_t slot) const;

    // The weight of a sample of density pf against the other technique's pg: the power
    // heuristic's inline code for the default, else mc/mis.h's general one.
    float misWeight(float pf, float pg) const {
        return defaultMis_ ? powerHeuristic(pf, pg) : float(mis_.weight(pf, pg));
    }

    const Scene& scene_;
    int maxDepth_;
    MisWeighting mis_;
    bool defaultMis_;
    int lightSamples_;
    float lightCount_;  // lightSamples_ as the MIS weights' sample count n_light
};

}  // namespace ps
