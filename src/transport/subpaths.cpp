#include "transport/subpaths.h"

#include <algorithm>
#include <limits>
#include <new>

#include "lights/infinity_disk.h"
#include "mc/primary_sample_sampler.h"
#include "media/transmittance.h"

namespace ps {

namespace {

Vec3 directionTo(const PathVertex& from, const PathVertex& to) { return normalize(to.p - from.p); }

}  // namespace

template <typename S>
int Subpaths::cameraSubpath(const Ray& ray, S& sampler, ScratchBuffer& scratch, PathStats& stats,
                            PathVertex* path, int maxVertices, SampledWavelengths* lambda,
                            const MediaSample* media) const {
    PathVertex& cam = path[0];
    resetVertex(cam);
    cam.kind = VertexKind::Camera;
    cam.mode = TransportMode::Radiance;
    cam.p = ray.o;
    cam.time = ray.time;
    cam.beta = Spectrum(1.0f);
    ++stats.cameraPaths;
    float pdfDir = 1;
    if (scene_.camera().hasImportance()) {
        pdfDir = scene_.camera().generatedRayPdfDir(ray);
        if (!(pdfDir > 0)) return 1;
    } else {
        // An orthographic, spherical or realistic camera cannot be reached by a connection
        // (no strategy with t = 1): marked delta, the MIS weights leave those strategies out
        // (thesis sec. 10.3.5), and the direction density, which only they would use, is a
        // placeholder.
        cam.delta = true;
    }
    int n = maxVertices > 0 ? std::min(maxVertices, maxCameraVertices()) : maxCameraVertices();
    if (media) {
        cam.mediumAbove = cam.mediumBelow = scene_.cameraMedium();
        return 1 + randomWalkInMedia(ray, scene_.cameraMedium(), cam.beta, pdfDir, sampler, stats, scratch, path + 1,
                                     n - 1, TransportMode::Radiance, kCameraStartDimensions, lambda, *media);
    }
    return 1 + randomWalk(ray, cam.beta, pdfDir, sampler, scratch, stats, path + 1, n - 1, TransportMode::Radiance,
                          kCameraStartDimensions, lambda);
}

template <typename S>
int Subpaths::lightSubpath(S& sampler, float time, ScratchBuffer& scratch, PathStats& stats, PathVertex* path,
                           SampledWavelengths* lambda, const MediaSample* media, LensHits* lens) const {
    LightOrigin origin = lightOrigin(sampler, time, stats, path, lambda);
    return continueLightSubpath(origin, sampler, scratch, stats, path, 0, lambda, media, lens);
}

template <typename S>
Subpaths::LightOrigin Subpaths::lightOrigin(S& sampler, float time, PathStats& stats, PathVertex* path,
                                            const SampledWavelengths* lambda) const {
    LightOrigin o;
    ++stats.lightPaths;
    float uLight = sampler.get1D();
    Vec2 uPos = sampler.get2D();
    Vec2 uDir = sampler.get2D();
    float pmf;
    const Light* light = scene_.sampleLight(uLight, &pmf);
    if (!light || !(pmf > 0)) return o;
    auto les = light->sampleLe(uPos, uDir, lambda);
    if (!les || !(les->pdfPos > 0) || !(les->pdfDir > 0) || les->L.isBlack()) return o;

    PathVertex& v = path[0];
    resetVertex(v);
    v.kind = VertexKind::Light;
    v.mode = TransportMode::Importance;
    v.light = light;
    v.infinite = light->atInfinity();
    v.p = les->ray.o;
    v.time = time;
    v.ng = v.ns = les->n;
    v.beta = les->L;
    v.pdfFwd = pmf * les->pdfPos;
    float cosLight = v.onSurface() ? std::fabs(dot(les->n, les->ray.d)) : 1.0f;
    o.beta = les->L * (cosLight / (pmf * les->pdfPos * les->pdfDir));
    if (!o.beta.isFinite()) {
        ++stats.guarded;
        return o;
    }
    o.ray = v.onSurface() ? spawnRay(les->ray.o, les->n, les->ray.d, time) : les->ray;
    o.ray.time = time;
    o.direction = les->ray.d;
    o.pdfPos = les->pdfPos;
    o.pdfDir = les->pdfDir;
    o.valid = true;
    if (scene_.hasMedia()) {
        v.mediumAbove = light->mediumOutside;
        v.mediumBelow = light->mediumInside;
        o.medium = light->mediumToward(les->n, les->ray.d);
    }
    return o;
}

template <typename S>
int Subpaths::continueLightSubpath(const LightOrigin& o, S& sampler, ScratchBuffer& scratch, PathStats& stats,
                                   PathVertex* path, int maxVertices, SampledWavelengths* lambda,
                                   const MediaSample* media, LensHits* lens) const {
    if (!o.valid) return 0;
    PathVertex& v = path[0];
    int limit = maxVertices > 0 ? std::min(maxVertices, maxLightVertices()) : maxLightVertices();
    int n = media ? randomWalkInMedia(o.ray, o.medium, o.beta, o.pdfDir, sampler, stats, scratch, path + 1, limit - 1,
                                      TransportMode::Importance, kLightStartDimensions, lambda, *media, lens)
                  : randomWalk(o.ray, o.beta, o.pdfDir, sampler, scratch, stats, path + 1, limit - 1,
                               TransportMode::Importance, kLightStartDimensions, lambda, lens);
    // From a disk at infinity the second vertex's density is the disk's area density
    // projected onto its surface, and the first is the directional density (thesis §10.2).
    if (v.infinite) {
        if (n > 0) {
            path[1].pdfFwd = o.pdfPos;
            if (path[1].onSurface()) path[1].pdfFwd *= densityCos(path[1], o.direction);
        }
        v.pdfFwd = infiniteLightDensity(-o.direction);
    }
    return 1 + n;
}

template <typename S>
int Subpaths::randomWalk(Ray ray, Spectrum beta, float pdfFwd, S& sampler, ScratchBuffer& scratch,
                         PathStats& stats, PathVertex* path, int maxVertices, TransportMode mode,
                         int firstDimension, SampledWavelengths* lambda, LensHits* lens) const {
    if (maxVertices <= 0) return 0;
    int bounces = 0, passThroughs = 0;
    Spectrum scatter(1.0f);  // the walk's own throughput, for Russian roulette
    float etaScale = 1;
    bool haveU = false;
    Vec2 u;
    while (true) {
        // The next direction sample does not depend on the hit: drawn before the ray is
        // traced, the sampler's hashing overlaps the traversal instead of following it.
        // Each vertex reads its own block of dimensions (see kDimensionsPerVertex).
        const int block = firstDimension + kDimensionsPerVertex * bounces;
        if (!haveU) {
            sampler.seekDimension(block);
            u = sampler.get2D();
        }
        haveU = true;
        SurfaceInteraction si;
        ++stats.rays;
        PathVertex& prev = path[bounces - 1];
        PathVertex& v = path[bounces];
        const bool hit = scene_.intersect(ray, si);
        // The lens vertex would be walk vertex `bounces`, light subpath vertex bounces + 1.
        if (lens)
            recordLensCrossing(scene_.camera(), ray,
                               hit ? dot(si.p - ray.o, ray.d) / lengthSquared(ray.d) : std::numeric_limits<float>::infinity(), bounces + 1,
                               beta, pdfFwd, *lens);
        if (!hit) {
            // A camera ray leaving the scene ends on the infinite lights (the s = 0 strategy).
            if (mode == TransportMode::Radiance && !scene_.infiniteLights().empty()) {
                initEscapeVertex(v, ray, beta, pdfFwd);
                ++bounces;
            }
            break;
        }
        const int terminationRequests = lambda ? lambda->terminationRequests : 0;
        const BxDF* bxdf = surfaceBxDF(si, scratch, lambda);
        if (!bxdf) {
            // `interface`: not a vertex; the ray continues and the density stays per solid angle.
            if (++passThroughs > 1024) break;  // a degenerate stack of coincident interfaces
            ray = spawnRay(si.p, si.ng, ray.d, ray.time);
            continue;
        }
        resetVertex(v);
        initSurfaceVertex(v, si, bxdf, mode, ray.time);
        v.dispersive = lambda && lambda->terminationRequests != terminationRequests;
        v.beta = beta;
        float toThisArea;
        areaFactors(prev, v, &toThisArea, &v.toPrevArea);
        v.pdfFwd = pdfFwd * toThisArea;
        Vec3 woLocal = v.woLocal;
        if (++bounces >= maxVertices) break;

        if (woLocal.z == 0) break;
        sampler.seekDimension(block + 2);
        float uc = bxdf->usesLobeSample() ? sampler.get1D() : 0.5f;
        haveU = false;
        SurfaceScatter sc;
        if (!scatterAtSurface(v, uc, u, mode, stats, sc)) break;
        beta *= sc.weight;
        scatter *= sc.weight;
        pdfFwd = sc.pdfFwd;
        etaScale *= sc.etaSq;
        const float pdfRev = sc.pdfRev;
        const Vec3 wi = sc.wi;
        prev.pdfRev = pdfRev * v.toPrevArea;
        ray = spawnRay(si.p, si.ng, wi, ray.time);
        if (beta.isBlack()) break;

        // Russian roulette on the walk's own throughput (radiance scaling of refraction undone),
        // after the second scattering as in the path tracer (thesis §2.5.3.2).
        float m = (scatter * etaScale).maxComponent();
        if (m < 1 && bounces > 1 && roulette_) {
            float q = std::max(0.0f, 1 - m);
            sampler.seekDimension(block + 3);
            if (sampler.get1D() < q) break;
            beta /= 1 - q;
            scatter /= 1 - q;
        }
    }
    return bounces;
}

template <typename S>
MediaSample Subpaths::mediaSample(S& sampler, const SampledWavelengths* lambda) const {
    MediaSample m;
    m.spectral = lambda != nullptr;
    m.lambda = lambda;
    // Past the time and the Metropolis wavelengths' value (chains.cpp).
    sampler.seekDimension(timeDimension() + 2);
    const float uHero = sampler.get1D();
    // The hero must be each channel with equal probability for the channel mean of the
    // densities to make an unbiased estimator; spectral mode's lambda[0] already is.
    if (!m.spectral) m.hero = std::min(2, int(uHero * 3));
    const float u0 = sampler.get1D(), u1 = sampler.get1D();
    m.seed = hashCombine(uint64_t(u0 * 16777216.0f), uint64_t(u1 * 16777216.0f));
    return m;
}

#define PS_SUBPATH_WALKS(S)                                                                                  \
    template int Subpaths::cameraSubpath<S>(const Ray&, S&, ScratchBuffer&, PathStats&, PathVertex*, int,      \
                                            SampledWavelengths*, const MediaSample*) const;                    \
    template int Subpaths::lightSubpath<S>(S&, float, ScratchBuffer&, PathStats&, PathVertex*,                 \
                                           SampledWavelengths*, const MediaSample*, LensHits*) const;          \
    template Subpaths::LightOrigin Subpaths::lightOrigin<S>(S&, float, PathStats&, PathVertex*,                 \
                                                            const SampledWavelengths*) const;                  \
    template int Subpaths::continueLightSubpath<S>(const LightOrigin&, S&, ScratchBuffer&, PathStats&,          \
                                                   PathVertex*, int, SampledWavelengths*, const MediaSample*,  \
                                                   LensHits*) const;                                           \
    template MediaSample Subpaths::mediaSample<S>(S&, const SampledWavelengths*) const;
PS_SUBPATH_WALKS(Sampler)
PS_SUBPATH_WALKS(PaddedSobolSampler)
PS_SUBPATH_WALKS(IndependentSampler)
PS_SUBPATH_WALKS(PrimarySampleSampler)
#undef PS_SUBPATH_WALKS

Spectrum Subpaths::f(const PathVertex& v, const PathVertex& next, TransportMode mode) const {
    Vec3 wi = directionTo(v, next);
    // The phase function is symmetric: no adjoint.
    if (v.kind == VertexKind::Medium) return Spectrum(v.mediumAbove->phase().p(v.wo, wi));
    if (v.kind != VertexKind::Surface || !v.bxdf) return {};
    Spectrum fv = v.bxdf->f(v.frame.toLocal(v.wo), v.frame.toLocal(wi), mode);
    if (mode == TransportMode::Importance && !v.flatShading) fv *= adjointShadingFactor(v.wo, wi, v.ns, v.ng);
    return fv;
}

float Subpaths::pdf(const PathVertex& v, const PathVertex* prev, const PathVertex& next, bool reverse) const {
    if (v.kind == VertexKind::Light) return pdfLight(v, next);
    Vec3 wn = next.p - v.p;
    if (!(lengthSquared(wn) > 0)) return 0;
    wn = normalize(wn);
    float pdfDir;
    if (v.kind == VertexKind::Camera) {
        float pdfPos;
        Ray toNext{v.p, wn};
        toNext.time = v.time;  // a moving lens where it is at the path's time
        scene_.camera().pdfWe(toNext, &pdfPos, &pdfDir);
    } else if (v.kind == VertexKind::Medium) {
        // Densities exclude the free flights' (MIS weights over channel-independent densities:
        // subpaths_media.cpp), so a medium vertex's is its phase function's alone.
        if (!prev) return 0;
        pdfDir = v.mediumAbove->phase().pdf(directionTo(v, *prev), wn);
    } else {
        if (!prev || !v.bxdf) return 0;
        Vec3 wp = directionTo(v, *prev);
        TransportMode mode = reverse ? adjoint(v.mode) : v.mode;
        pdfDir = v.bxdf->pdf(v.frame.toLocal(wp), v.frame.toLocal(wn), mode);
    }
    return solidAngleToArea(v, pdfDir, next);
}

void Subpaths::emissionDensities(const PathVertex& v, const PathVertex& to, float* origin, float* next) const {
    Vec3 d = to.p - v.p;
    float d2 = lengthSquared(d);
    Vec3 w = d / std::sqrt(d2);
    bool nextDefined = d2 > 0;  // coincident points: `to` has no density (and w is not a direction)
    if (next) *next = 0;
    if (!origin && !nextDefined) return;
    if (v.isInfiniteLight()) {
        if (origin) *origin = infiniteLightDensity(-w);
        if (next && nextDefined) *next = infinityDiskPdf(scene_.boundsRadius());
    } else {
        if (origin) *origin = 0;
        if (!v.light) return;
        float pdfPos, pdfDir;
        v.light->pdfLe(v.p, v.ng, w, &pdfPos, &pdfDir);
        if (origin) *origin = scene_.lightPmf(v.light) * pdfPos;
        if (next && nextDefined) *next = pdfDir / d2;
    }
    if (next && nextDefined && to.onSurface()) *next *= densityCos(to, w);
}

float Subpaths::pdfLightOrigin(const PathVertex& v, const PathVertex& to) const {
    float origin;
    emissionDensities(v, to, &origin, nullptr);
    return origin;
}

float Subpaths::pdfLight(const PathVertex& v, const PathVertex& to) const {
    float next;
    emissionDensities(v, to, nullptr, &next);
    return next;
}

Spectrum Subpaths::Le(const PathVertex& v, const PathVertex& to, const SampledWavelengths* lambda) const {
    if (!v.isLight()) return {};
    Vec3 w = directionTo(v, to);
    if (v.isInfiniteLight()) {
        Spectrum L;
        for (const Light* light : scene_.infiniteLights()) L += light->Le(Ray{v.p, -w}, lambda);
        return L;
    }
    return v.light->L(v.p, v.ng, v.uv, w, lambda);
}

bool Subpaths::visible(const PathVertex& a, const PathVertex& b, PathStats& stats) const {
    ++stats.shadowRays;
    return !scene_.occluded(spawnRayTo(a.p, a.ng, b.p, a.time));  // both ends share the path's time
}

bool Subpaths::connectThrough(const PathVertex& a, const PathVertex& b, const Spectrum& rU, PathStats& stats,
                              const MediaSample* media, uint64_t stream, Spectrum& L) const {
    if (!media) return visible(a, b, stats);
    ++stats.shadowRays;
    Rng rng(hashCombine(media->seed, stream));
    const TransmittanceEstimate tr = transmittance(scene_, a.p, a.ng, a.mediumToward(b.p - a.p), b.p, a.time,
                                                   media->lambda, media->hero, media->spectral, rng);
    stats.rays += tr.rays > 0 ? uint64_t(tr.rays - 1) : 0;
    if (tr.T.isBlack()) return false;
    // Ratio tracking sampled its null collisions by the hero's majorant: tr.rL is each
    // channel's density of them relative to the hero's, a factor of the path's densities.
    L *= tr.T / channelMean(rU * tr.rL, media->spectral);
    return true;
}

float Subpaths::lightChoiceRatio(const PathVertex& y0, const PathVertex& y1) const {
    const LightSampler& sampler = scene_.lightSampler();
    const LightSampleContext ctx{y1.p, y1.ng};
    const bool deltaDirection = y0.light && y0.light->type() == LightType::DeltaDirection;
    if (y0.isInfiniteLight() && !deltaDirection) {
        // Any light at infinity may have given the direction: the densities of all of them.
        const Vec3 w = directionTo(y1, y0);
        double atPoint = 0, byEmission = 0;
        for (const Light* light : scene_.infiniteLights()) {
            const double pdf = light->pdfLi(LightSampleContext{}, w, nullptr);
            atPoint += double(sampler.pmf(ctx, light)) * pdf;
            byEmission += double(scene_.lightPmf(light)) * pdf;
        }
        return byEmission > 0 ? float(atPoint / byEmission) : 0.0f;
    }
    if (!y0.light) return 0;
    const float byEmission = scene_.lightPmf(y0.light);
    return byEmission > 0 ? sampler.pmf(ctx, y0.light) / byEmission : 0.0f;
}

float Subpaths::infiniteLightDensity(Vec3 wToLight) const {
    float pdf = 0;
    for (const Light* light : scene_.infiniteLights())
        pdf += scene_.lightPmf(light) * light->pdfLi(LightSampleContext{}, wToLight, nullptr);
    return pdf;
}

}  // namespace ps
