#include "transport/path_tracer.h"

namespace ps {

Spectrum PathTracer::sampleDirect(const SurfaceInteraction& si, const Frame& frame, const BxDF& bxdf, Vec3 woLocal,
                                  float uLight, Vec2 u, float time, const SampledWavelengths* lambda,
                                  PathStats& stats, const Spectrum& beta, const ShadowRoulette& roulette,
                                  uint64_t slot) const {
    // The light is chosen for this point (the scene's "lightsampler"); the MIS weights of
    // emitters the next ray hits ask the same sampler at the same point (prevCtx).
    const LightSampleContext ctx{si.p, si.ng, lambda};
    const SampledLight sl = scene_.lightSampler().sample(ctx, uLight);
    const Light* light = sl.light;
    const float pmf = sl.pmf;
    if (!light || !(pmf > 0)) return {};
    auto ls = light->sampleLi(ctx, u);
    if (!ls || ls->L.isBlack() || !(ls->pdf > 0)) return {};
    Vec3 wiLocal = frame.toLocal(ls->wi);
    Spectrum f = bxdf.f(woLocal, wiLocal, TransportMode::Radiance) * absCosTheta(wiLocal);
    if (f.isBlack()) return {};
    const float pLight = pmf * ls->pdf;
    // The contribution if unoccluded; the MIS weight's BSDF density (costly for layered
    // BxDFs) waits for the shadow ray unless the roulette needs it first. With N light
    // samples the light technique's density counts N times (n_i p_i, thesis eq. 9.8-9.13).
    const auto unoccluded = [&] {
        if (light->isDelta()) return f * ls->L / pLight;
        const float pBsdf = bxdf.pdf(woLocal, wiLocal, TransportMode::Radiance);
        return f * ls->L * (misWeight(lightCount_ * pLight, pBsdf) / pLight);
    };
    Spectrum C;
    float scale = 1;
    if (roulette.active()) {
        C = unoccluded();
        if (!roulette.trace(beta * C, slot, &scale)) {
            ++stats.shadowRaysSkipped;
            return {};
        }
    }
    ++stats.shadowRays;
    if (scene_.occluded(spawnRayTo(si.p, si.ng, ls->pLight, time))) return {};
    return roulette.active() ? C * scale : unoccluded();
}

std::vector<RenderTechnique> PathTracer::techniques() const {
    if (scene_.hasMedia()) return {};
    return {{"light"}, {"bsdf"}};
}

Spectrum PathTracer::Li(const Ray& ray, SampleContext& ctx) const {
    if (scene_.hasMedia()) return estimateInMedia(ray, ctx.sampler, ctx.scratch, ctx.stats, ctx.lambda);
    return withConcreteSampler(ctx.sampler, [&](auto& sampler) {
        // The plain instance is the estimator as it was before splitting and the figures existed
        // (bit for bit the same images); the other adds them.
        return ctx.tally || lightSamples_ > 1 ? estimate<true>(ray, sampler, ctx) : estimate<false>(ray, sampler, ctx);
    });
}

template <bool Split, typename S>
Spectrum PathTracer::estimate(const Ray& cameraRay, S& sampler, SampleContext& ctx) const {
    ScratchBuffer& scratch = ctx.scratch;
    PathStats& stats = ctx.stats;
    SampledWavelengths* lambda = ctx.lambda;
    const ShadowRoulette& roulette = ctx.roulette;
    Spectrum L, beta(1.0f);
    Spectrum lightPart;  // Split: the light technique's part of L (the rest is BSDF sampling's)
    Ray ray = cameraRay;
    int depth = 0;
    bool specularBounce = false;
    float etaScale = 1;     // product of eta'^2 over refractions, for roulette
    float prevBsdfPdf = 0;  // solid-angle pdf of the direction just sampled
    LightSampleContext prevCtx;
    ++stats.cameraPaths;

    bool haveSamples = false;
    float uLight = 0;
    Vec2 uLightPoint, uBsdf;
    while (true) {
        // This vertex's light and BSDF samples do not depend on the hit: drawn before the ray
        // is traced, the sampler's hashing overlaps the traversal instead of following it.
        if (!haveSamples) {
            uBsdf = sampler.get2D();
            uLight = sampler.get1D();
            uLightPoint = sampler.get2D();
            haveSamples = true;
        }
        SurfaceInteraction si;
        ++stats.rays;
        if (!scene_.intersect(ray, si)) {
            for (const Light* light : scene_.infiniteLights()) {
                Spectrum Le = light->Le(ray, lambda);
                if (Le.isBlack()) continue;
                if (depth == 0 || specularBounce) {
                    L += beta * Le;
                } else {
                    float pl = scene_.lightSampler().pmf(prevCtx, light) * light->pdfLi(prevCtx, ray.d, nullptr);
                    L += beta * Le * misWeight(prevBsdfPdf, Split ? lightCount_ * pl : pl);
                }
            }
            break;
        }

        // Emission found by the path (s = 0 strategy), MIS-weighted against light sampling.
        if (si.areaLight) {
            Spectrum Le = si.areaLight->L(si.p, si.ng, si.uv, si.wo, lambda);
            if (!Le.isBlack()) {
                if (depth == 0 || specularBounce) {
                    L += beta * Le;
                } else {
                    float pl = scene_.lightSampler().pmf(prevCtx, si.areaLight) * si.areaLight->pdfLi(prevCtx, ray.d, &si);
                    L += beta * Le * misWeight(prevBsdfPdf, Split ? lightCount_ * pl : pl);
                }
            }
        }

        const BxDF* bxdf = surfaceBxDF(si, scratch, lambda);
        if (!bxdf) {
            // `interface`: not a scattering event; continue straight through.
            specularBounce = true;
            ray = spawnRay(si.p, si.ng, ray.d, ray.time);
            continue;
        }
        if (depth++ == maxDepth_) break;

        Frame frame = si.shadingFrame();
        Vec3 woLocal = frame.toLocal(si.wo);
        if (woLocal.z == 0) break;
        // The next direction first, so that the next ray does not wait behind the shadow ray.
        float uc = bxdf->usesLobeSample() ? sampler.get1D() : 0.5f;
        auto bs = bxdf->sample(woLocal, uc, uBsdf, TransportMode::Radiance);
        haveSamples = false;
        uint8_t flags = bxdf->flags();
        if (flags & (kDiffuse | kGlossy)) {
            if constexpr (!Split) {
                L += beta * sampleDirect(si, frame, *bxdf, woLocal, uLight, uLightPoint, ray.time, lambda, stats, beta,
                                         roulette, uint64_t(depth));
            } else {
                Spectrum direct = sampleDirect(si, frame, *bxdf, woLocal, uLight, uLightPoint, ray.time, lambda, stats,
                                               beta, roulette, uint64_t(depth));
                // Splitting (--light-samples N): N - 1 more light samples, each counting 1 / N.
                if (lightSamples_ > 1) {
                    for (int i = 1; i < lightSamples_; ++i) {
                        const float u1 = sampler.get1D();
                        const Vec2 u2 = sampler.get2D();
                        direct += sampleDirect(si, frame, *bxdf, woLocal, u1, u2, ray.time, lambda, stats, beta,
                                               roulette, uint64_t(depth) | uint64_t(i) << 32);
                    }
                    direct /= lightCount_;
                }
                L += beta * direct;
                lightPart += beta * direct;
            }
        }
        if (!bs || !(bs->pdf > 0) || bs->f.isBlack()) break;
        Vec3 wi = frame.toWorld(bs->wi);
        Spectrum weight = bs->f * (absCosTheta(bs->wi) / bs->pdf);
        if (!weight.isFinite()) {
            ++stats.guarded;
            break;
        }
        beta *= weight;
        // Layered BxDFs only know their pdf up to a factor; MIS needs the true density.
        prevBsdfPdf = bs->pdfIsProportional ? bxdf->pdf(woLocal, bs->wi, TransportMode::Radiance) : bs->pdf;
        specularBounce = bs->isSpecular();
        if (bs->isTransmission()) etaScale *= sqr(bs->eta);
        prevCtx = LightSampleContext{si.p, si.ng};  // where sampleDirect chose its light
        ray = spawnRay(si.p, si.ng, wi, ray.time);

        // Russian roulette on the throughput with the radiance scaling of refraction undone.
        Spectrum rrBeta = beta * etaScale;
        float m = rrBeta.maxComponent();
        if (m < 1 && depth > 1) {
            float q = std::max(0.0f, 1 - m);
            if (sampler.get1D() < q) break;
            beta /= 1 - q;
        }
    }
    if constexpr (Split) {
        if (ctx.tally) {
            ctx.tally->addCamera(kLightTechnique, ctx.toFilm(lightPart));
            ctx.tally->addCamera(kBsdfTechnique, ctx.toFilm(L - lightPart));
        }
    }
    return L;
}

}  // namespace ps
