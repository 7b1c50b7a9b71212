// The path tracer in scenes with participating media: pbrt-v4's volpath. Free flights are
// sampled by delta tracking against each medium's majorant, shadow rays by ratio tracking
// (media/transmittance.h); every channel's throughput follows the hero channel's sampling,
// and the estimate divides by the channel mean of the path densities, rU (the walk's) and
// rL (light sampling's): spectral MIS over wavelengths (Wilkie et al. 2014, pbrt-v4 §14.2),
// which also combines light and scattering sampling by the balance heuristic. In RGB mode the
// three channels play the wavelengths' part and the hero is drawn per path.
#include "mc/mis.h"
#include "media/delta_tracking.h"
#include "media/transmittance.h"
#include "transport/path_tracer.h"

namespace ps {

namespace {

struct VolPathState {
    Spectrum L, beta{1.0f}, rU{1.0f}, rL{1.0f};
    int hero = 0;
    bool spectral = false;
    float mean(const Spectrum& s) const { return channelMean(s, spectral); }
};

}  // namespace

// One light sample at a surface (bxdf set) or medium vertex (bxdf null: the phase function),
// weighted as pbrt-v4's SampleLd: f T L / mean(rU_path (p_light + p_scatter)).
Spectrum PathTracer::sampleDirectInMedia(const VolVertex& v, const Spectrum& beta, const Spectrum& rPath, int hero, Sampler& sampler,
                                         Rng& rng, const SampledWavelengths* lambda, PathStats& stats) const {
    const float uLight = sampler.get1D();
    const Vec2 u = sampler.get2D();
    const LightSampleContext ctx{v.p, v.ng, lambda};
    const SampledLight sl = scene_.lightSampler().sample(ctx, uLight);
    if (!sl.light || !(sl.pmf > 0)) return {};
    auto ls = sl.light->sampleLi(ctx, u);
    if (!ls || ls->L.isBlack() || !(ls->pdf > 0)) return {};
    Spectrum f;
    float scatterPdf;
    if (v.bxdf) {
        const Vec3 wiLocal = v.frame.toLocal(ls->wi);
        f = v.bxdf->f(v.woLocal, wiLocal, TransportMode::Radiance) * absCosTheta(wiLocal);
        scatterPdf = v.bxdf->pdf(v.woLocal, wiLocal, TransportMode::Radiance);
    } else {
        const float p = v.medium->phase().p(v.wo, ls->wi);
        f = Spectrum(p);
        scatterPdf = p;
    }
    if (f.isBlack()) return {};
    ++stats.shadowRays;
    const Medium* medium = v.bxdf ? v.si->mediumToward(ls->wi, v.medium) : v.medium;
    TransmittanceEstimate tr = transmittance(scene_, v.p, v.ng, medium, ls->pLight, v.time, lambda, hero, lambda != nullptr, rng);
    stats.rays += tr.rays > 0 ? uint64_t(tr.rays - 1) : 0;
    if (tr.T.isBlack()) return {};
    const float pLight = sl.pmf * ls->pdf;
    const Spectrum rL = rPath * tr.rL * pLight, rU = rPath * tr.rU * scatterPdf;
    const bool spectral = lambda != nullptr;
    if (sl.light->isDelta()) return beta * f * tr.T * ls->L / channelMean(rL, spectral);
    return beta * f * tr.T * ls->L / channelMean(rL + rU, spectral);
}

Spectrum PathTracer::estimateInMedia(const Ray& cameraRay, Sampler& sampler, ScratchBuffer& scratch, PathStats& stats,
                                     SampledWavelengths* lambda) const {
    VolPathState st;
    st.spectral = lambda != nullptr;
    // The hero channel must be any of them with equal probability for the mean of the
    // channels' densities to make an unbiased estimator; spectral mode's lambda[0] already is.
    if (!st.spectral) st.hero = std::min(2, int(sampler.get1D() * 3));
    Rng rng(hashCombine(uint64_t(sampler.get1D() * 16777216.0f), uint64_t(sampler.get1D() * 16777216.0f)));
    Ray ray = cameraRay;
    const Medium* medium = scene_.cameraMedium();
    int depth = 0;
    bool specularBounce = false;
    float etaScale = 1;
    LightSampleContext prevCtx;
    ++stats.cameraPaths;
    const int h = st.hero;

    while (true) {
        SurfaceInteraction si;
        ++stats.rays;
        const bool hit = scene_.intersect(ray, si);
        if (medium) {
            const float tEnd = hit ? si.t : std::numeric_limits<float>::infinity();
            const Flight fl = deltaTrack(*medium, ray, tEnd, sampler.get1D(), rng, lambda, h, st.beta, st.rU, &st.rL,
                                         [&](const MediumProperties& mp, const Spectrum& sigmaMaj, const Spectrum& Tm) {
                // Emission along the flight (pbrt-v4 adds sigma_a Le at every tentative collision).
                if (depth < maxDepth_) st.L += emissionAtCollision(mp, sigmaMaj, Tm, st.beta, st.rU, h, st.spectral);
            });
            if (fl.end == FlightEnd::Absorbed || !st.beta.isFinite()) return st.L;
            if (fl.end == FlightEnd::Scattered) {
                if (depth++ >= maxDepth_) return st.L;
                VolVertex v;
                v.p = fl.p;
                v.wo = -normalize(ray.d);
                v.medium = medium;
                v.time = ray.time;
                st.L += sampleDirectInMedia(v, st.beta, st.rU, h, sampler, rng, lambda, stats);
                float phasePdf = 0;
                const Vec3 wi = medium->phase().sample(v.wo, sampler.get2D(), &phasePdf);
                if (!(phasePdf > 0)) return st.L;
                // HG samples its own density: p / pdf = 1.
                st.rL = st.rU / phasePdf;
                prevCtx = LightSampleContext{fl.p, Vec3(0, 0, 0)};
                ray = Ray{fl.p, wi, std::numeric_limits<float>::infinity(), ray.time};
                specularBounce = false;
                continue;
            }
        }

        // Emission found by the walk, weighed against light sampling from the previous vertex
        // (whose density joins rL) unless that vertex could not sample lights.
        auto addEmission = [&](const Spectrum& Le, const Light* light, const SurfaceInteraction* at) {
            if (Le.isBlack()) return;
            if (depth == 0 || specularBounce) {
                st.L += st.beta * Le / st.mean(st.rU);
                return;
            }
            const float pl = scene_.lightSampler().pmf(prevCtx, light) * light->pdfLi(prevCtx, normalize(ray.d), at);
            st.L += st.beta * Le / st.mean(st.rU + st.rL * pl);
        };
        if (!hit) {
            for (const Light* light : scene_.infiniteLights()) addEmission(light->Le(ray, lambda), light, nullptr);
            break;
        }
        if (si.areaLight) addEmission(si.areaLight->L(si.p, si.ng, si.uv, si.wo, lambda), si.areaLight, &si);

        const BxDF* bxdf = surfaceBxDF(si, scratch, lambda);
        if (!bxdf) {
            // `interface`: no vertex and no change of throughput; only the medium changes.
            medium = si.mediumToward(ray.d, medium);
            ray = spawnRay(si.p, si.ng, ray.d, ray.time);
            continue;
        }
        if (depth++ >= maxDepth_) break;
        VolVertex v;
        v.si = &si;
        v.bxdf = bxdf;
        v.frame = si.shadingFrame();
        v.woLocal = v.frame.toLocal(si.wo);
        v.p = si.p;
        v.ng = si.ng;
        v.medium = medium;
        v.time = ray.time;
        if (v.woLocal.z == 0) break;
        if (bxdf->flags() & (kDiffuse | kGlossy)) st.L += sampleDirectInMedia(v, st.beta, st.rU, h, sampler, rng, lambda, stats);
        prevCtx = LightSampleContext{si.p, si.ng};
        const float uc = bxdf->usesLobeSample() ? sampler.get1D() : 0.5f;
        auto bs = bxdf->sample(v.woLocal, uc, sampler.get2D(), TransportMode::Radiance);
        if (!bs || !(bs->pdf > 0) || bs->f.isBlack()) break;
        const Vec3 wi = v.frame.toWorld(bs->wi);
        const Spectrum weight = bs->f * (absCosTheta(bs->wi) / bs->pdf);
        if (!weight.isFinite()) {
            ++stats.guarded;
            break;
        }
        st.beta *= weight;
        st.rL = st.rU / (bs->pdfIsProportional ? bxdf->pdf(v.woLocal, bs->wi, TransportMode::Radiance) : bs->pdf);
        specularBounce = bs->isSpecular();
        if (bs->isTransmission()) etaScale *= sqr(bs->eta);
        // Crossing a boundary with a MediumInterface by transmission changes medium.
        medium = si.mediumToward(wi, medium);
        ray = spawnRay(si.p, si.ng, wi, ray.time);

        const Spectrum rrBeta = st.beta * etaScale / st.mean(st.rU);
        const float uRR = sampler.get1D();
        const float m = rrBeta.maxComponent();
        if (m < 1 && depth > 1) {
            const float q = std::max(0.0f, 1 - m);
            if (uRR < q) break;
            st.beta /= 1 - q;
        }
    }
    return st.L;
}

}  // namespace ps
