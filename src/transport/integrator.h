// An integrator estimates the radiance arriving along a camera ray.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include "geometry/ray.h"
#include "film/film.h"
#include "materials/material.h"
#include "materials/shading_detail.h"
#include "math/spectrum.h"
#include "mc/sampler.h"
#include "render/scene.h"
#include "transport/shadow_roulette.h"
#include "transport/technique_tally.h"
#include "util/scratch.h"

namespace ps {

class SpectralFilm;

// Per-thread counters, summed at the end of a render.
struct PathStats {
    uint64_t cameraPaths = 0;
    uint64_t lightPaths = 0;  // light subpaths (light tracing, BDPT)
    uint64_t rays = 0;        // closest-hit rays, camera rays included
    uint64_t shadowRays = 0;  // visibility tests
    uint64_t guarded = 0;     // non-finite values caught at their source
    uint64_t shadowRaysSkipped = 0;  // visibility tests left out by roulette (transport/shadow_roulette.h)
    PathStats& operator+=(const PathStats& o) {
        cameraPaths += o.cameraPaths; lightPaths += o.lightPaths; rays += o.rays; shadowRays += o.shadowRays; guarded += o.guarded;
        shadowRaysSkipped += o.shadowRaysSkipped;
        return *this;
    }
    // What a run added to the counts `before` it (a resumed render's own work).
    PathStats since(const PathStats& before) const {
        return {cameraPaths - before.cameraPaths, lightPaths - before.lightPaths, rays - before.rays,
                shadowRays - before.shadowRays, guarded - before.guarded, shadowRaysSkipped - before.shadowRaysSkipped};
    }
};

// The BxDF at a surface hit (textures evaluated, `mix` resolved), allocated in scratch;
// nullptr for `interface` materials, which do not scatter. A bump or normal map of the
// resolved material replaces si's shading frame first (ns, dpdu): every integrator builds
// its frame from si after this call, so all of them use the mapped one. In spectral mode
// (lambda not null) the textures are evaluated at the path's wavelengths, and the BxDFs
// built once for RGB mode are not used.
inline const BxDF* surfaceBxDF(SurfaceInteraction& si, ScratchBuffer& scratch, SampledWavelengths* lambda = nullptr) {
    if (!si.material) return nullptr;
    const bool maps = si.material->needsShadingDerivatives();
    if (!maps && !lambda)
        if (const BxDF* b = si.material->constantBxDF()) return b;
    MaterialEvalContext ctx;
    ctx.lambda = lambda;
    ctx.p = si.p;
    ctx.n = si.ng;  // textures see the geometric normal, as pbrt-v4's do
    ctx.uv = si.uv;
    ctx.wo = si.wo;
    ctx.dpdu = si.dpdu;
    ctx.fibre = si.fibre;
    const Material* material = si.material->resolve(ctx);
    if (!material) return nullptr;
    if (maps) {
        if (const ShadingDetail* detail = material->shadingDetail()) {
            detail->apply(si);
            ctx.dpdu = si.dpdu;
        }
    }
    if (!lambda)
        if (const BxDF* b = material->constantBxDF()) return b;
    return material->bxdf(ctx, scratch);
}

// What one camera sample's estimator works with.
struct SampleContext {
    Sampler& sampler;
    ScratchBuffer& scratch;
    PathStats& stats;
    Film& film;           // for splats (light-path contributions landing on any pixel)
    int sampleIndex = 0;  // the pixel sample's index (splats alternate half-buffers by it)
    int px = 0, py = 0;   // the pixel
    float filterWeight = 1;  // the camera sample's filter weight f/pdf
    // Spectral mode: the sample's wavelengths (null in RGB mode). Li returns the values at
    // them; a dispersive interface may terminate the secondary ones (their pdf becomes 0).
    SampledWavelengths* lambda = nullptr;
    // Spectral mode: the film's sensor, through which splats go (toFilm) as Li's result does.
    const SpectralFilm* sensor = nullptr;
    // Roulette on this sample's visibility tests (off unless --shadow-roulette).
    ShadowRoulette roulette;
    // `--stats`: where Li reports each technique's contribution (Integrator::techniques);
    // null otherwise, and then Li does no work for it.
    TechniqueTally* tally = nullptr;
    // A splat's value as the film takes it: the rendering space's RGB. Splats are made after
    // both subpaths exist, so the wavelengths' termination is final by then.
    Spectrum toFilm(const Spectrum& L) const;
};

class Integrator {
public:
    virtual ~Integrator() = default;
    // The estimate for the camera ray's own pixel; light-path strategies may also splat.
    virtual Spectrum Li(const Ray& ray, SampleContext& ctx) const = 0;
    // True if the integrator splats; each camera sample then also traces one light path,
    // and the film normalises splats by the number of samples taken.
    virtual bool splats() const { return false; }
    // Whether Li handles SampleContext::lambda (spectral mode, `--color spectral`).
    virtual bool supportsSpectral() const { return false; }
    // The techniques whose contributions Li reports to SampleContext::tally, indexed as it
    // reports them (transport/technique_tally.h); none: the integrator reports none.
    virtual std::vector<RenderTechnique> techniques() const { return {}; }
};

// Names: "path", "light", "bdpt", "pssmlt", "mmlt" (Markov chains over BDPT: render() runs its own
// driver, transport/mlt/); mis: the MIS heuristic (parseMisWeighting's syntax) of path,
// bdpt, pssmlt and mmlt, empty for the default (power, beta 2). Throws InputError for an
// unknown name, a bad heuristic, or a heuristic given where nothing is weighted by one
// (light, mlt) or only the balance heuristic applies (path in a scene with media).
std::unique_ptr<Integrator> createIntegrator(const std::string& name, const Scene& scene,
                                             const std::string& mis = "");

// --two-stage's fraction for a Metropolis integrator: `setting` if >= 0, else its default.
double metropolisTwoStage(const std::string& name, double setting);

// For benchmarks and tests: "NAME" or "NAME:KEY=VALUE,..." with mlt's --mlt-mutations keys,
// two-stage=F (--two-stage, pssmlt, mmlt and mlt) and black-level=L0
// (--two-stage-black-level), set in `st` (the others reset); returns NAME.
std::string applyIntegratorVariant(const std::string& spec, RenderSettings& st);

}  // namespace ps
