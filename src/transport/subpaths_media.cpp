// Camera and light random walks in scenes with participating media (issue 36): Subpaths'
// walk with free flights sampled by delta tracking (media/delta_tracking.h, shared with the
// path tracer), medium vertices whose "BSDF" is the phase function, and medium changes where
// the walk crosses a boundary. A separate function, chosen once per subpath, so that the walk
// of scenes without media does no per-vertex work for them.
//
// Densities. A vertex's pdfFwd and pdfRev here are those of the directions and geometry alone
// (phase or BSDF density times |cos| / d^2, or 1 / d^2 at a medium vertex: the volume measure,
// thesis ch. 8): the free flights' factors (sigma_s T per channel) are left out, so the MIS
// weights over strategies are one function of the path whatever the hero channel. Any such
// partition of unity keeps BDPT unbiased (thesis §9.2); the flights' channel-dependent
// densities enter instead through spectral MIS: each vertex's rU holds the ratios of every
// channel's density of the flights so far to the hero's, and a strategy's contribution
// divides by the channel mean of its whole path's ratios (both subpaths' and the connection's
// tracking: Subpaths::connectThrough), which with a uniformly drawn hero is the balance
// heuristic over channels (Wilkie et al. 2014) for every strategy.
//
// The t = 0 strategy (lens_hits.h, thesis §10.2): a light walk's segment that crosses a thin
// lens records the crossing if its free flight passes the lens before it collides. The flight
// is tracked to the lens and, past it, on to the segment's end afresh: the majorant's Poisson
// process is memoryless, so the split leaves the walk's distribution as it was (sampleMajorant
// restarts at its segments' ends likewise), and the part before the lens is the estimate of
// the transmittance to it that the walk's flights to surfaces make (deltaTrack's Passed:
// T_maj / pdf and the null collisions' ratios, in beta and rU alike).
#include <limits>

#include "mc/primary_sample_sampler.h"
#include "media/delta_tracking.h"
#include "transport/subpaths.h"

namespace ps {

template <typename S>
int Subpaths::randomWalkInMedia(Ray ray, const Medium* medium, Spectrum beta0, float pdfFwd, S& sampler,
                                PathStats& stats, ScratchBuffer& scratch, PathVertex* path, int maxVertices,
                                TransportMode mode, int firstDimension, SampledWavelengths* lambda,
                                const MediaSample& media, LensHits* lens) const {
    if (maxVertices <= 0) return 0;
    const uint64_t stream = mode == TransportMode::Radiance ? MediaSample::kCameraWalk : MediaSample::kLightWalk;
    Rng rng(hashCombine(media.seed, stream));
    int bounces = 0, passThroughs = 0;
    // The walk's own throughput (beta = beta0 scatter), for Russian roulette, and the
    // channels' flight densities relative to the hero's.
    Spectrum scatter(1.0f), rU(1.0f);
    float etaScale = 1;
    // Camera walks collect the media's emission along each flight, into the vertex the flight
    // leaves, at the depths the path tracer does (volpath: fewer than maxdepth scatterings
    // before it). Light walks have no use for it: emission inside a medium is no light
    // subpath's origin.
    const bool camera = mode == TransportMode::Radiance;
    PathVertex* from = nullptr;
    auto emission = [&](const MediumProperties& mp, const Spectrum& sigmaMaj, const Spectrum& Tm) {
        if (from) from->mediumLe += emissionAtCollision(mp, sigmaMaj, Tm, beta0 * scatter, rU, media.hero, media.spectral);
    };
    int flightBlock = -1;  // the block whose flight numbers were read (a second flight, past an interface, draws from rng)
    while (true) {
        const int block = firstDimension + kDimensionsPerMediaVertex * bounces;
        SurfaceInteraction si;
        ++stats.rays;
        PathVertex& prev = path[bounces - 1];
        PathVertex& v = path[bounces];
        const bool hit = scene_.intersect(ray, si);
        bool scattered = false;
        const float tEnd = hit ? si.t : std::numeric_limits<float>::infinity();
        // The lens vertex would be walk vertex `bounces`, light subpath vertex bounces + 1.
        const auto crossing = lens ? lensCrossing(scene_.camera(), ray, tEnd, bounces + 1, *lens) : std::nullopt;
        const auto recordCrossing = [&] {
            const float mean = channelMean(rU, media.spectral);
            if (mean > 0) recordLensHit(*crossing, bounces + 1, beta0 * scatter / mean, pdfFwd, *lens);
        };
        if (crossing && !medium) recordCrossing();
        if (medium) {
            float uFlight = rng.uniform(), uEvent = -1;
            if (flightBlock != block) {
                flightBlock = block;
                sampler.seekDimension(block + 4);
                uFlight = sampler.get1D();
                uEvent = sampler.get1D();
            }
            from = camera && bounces < maxDepth_ && medium->emissive() ? &prev : nullptr;
            Flight fl;
            Ray flightRay = ray;
            float flightEnd = tEnd;
            if (crossing) {
                // To the lens first, then (having passed it) on from the lens point afresh.
                fl = deltaTrack(*medium, ray, crossing->t, uFlight, rng, lambda, media.hero, scatter, rU, nullptr,
                                emission, uEvent);
                if (fl.end == FlightEnd::Passed && scatter.isFinite()) {
                    recordCrossing();
                    flightRay = Ray{crossing->p, ray.d, std::numeric_limits<float>::infinity(), ray.time};
                    flightEnd = tEnd - crossing->t;
                    uFlight = rng.uniform();
                    uEvent = -1;
                }
            }
            if (fl.end == FlightEnd::Passed && scatter.isFinite())
                fl = deltaTrack(*medium, flightRay, flightEnd, uFlight, rng, lambda, media.hero, scatter, rU, nullptr,
                                emission, uEvent);
            if (fl.end == FlightEnd::Absorbed || !scatter.isFinite()) break;
            if (fl.end == FlightEnd::Scattered) {
                scattered = true;
                resetVertex(v);
                v.kind = VertexKind::Medium;
                v.mode = mode;
                v.p = fl.p;
                v.time = ray.time;
                v.wo = -normalize(ray.d);
                v.mediumAbove = v.mediumBelow = medium;
                v.nonSpecular = true;
                v.beta = beta0 * scatter;
                v.rU = rU;
                float toThisVolume;
                areaFactors(prev, v, &toThisVolume, &v.toPrevArea);
                v.pdfFwd = pdfFwd * toThisVolume;
                if (++bounces >= maxVertices) break;
                sampler.seekDimension(block);
                float phasePdf = 0;
                const Vec3 wi = medium->phase().sample(v.wo, sampler.get2D(), &phasePdf);
                if (!(phasePdf > 0)) break;
                // HG samples its own density (p / pdf = 1) and is symmetric: the reverse
                // walk's density of wo from wi is the same.
                pdfFwd = phasePdf;
                prev.pdfRev = phasePdf * v.toPrevArea;
                ray = Ray{fl.p, wi, std::numeric_limits<float>::infinity(), ray.time};
            }
        }
        if (!scattered) {
            if (!hit) {
                // A camera ray leaving the scene ends on the infinite lights (the s = 0 strategy).
                if (mode == TransportMode::Radiance && !scene_.infiniteLights().empty()) {
                    initEscapeVertex(v, ray, beta0 * scatter, pdfFwd);
                    v.rU = rU;
                    ++bounces;
                }
                break;
            }
            const int terminationRequests = lambda ? lambda->terminationRequests : 0;
            const BxDF* bxdf = surfaceBxDF(si, scratch, lambda);
            if (!bxdf) {
                // `interface`: not a vertex; only the medium changes.
                if (++passThroughs > 1024) break;
                medium = si.mediumToward(ray.d, medium);
                ray = spawnRay(si.p, si.ng, ray.d, ray.time);
                continue;
            }
            resetVertex(v);
            initSurfaceVertex(v, si, bxdf, mode, ray.time);
            v.dispersive = lambda && lambda->terminationRequests != terminationRequests;
            v.beta = beta0 * scatter;
            v.rU = rU;
            v.mediumAbove = si.mediumTransition ? si.mediumOutside : medium;
            v.mediumBelow = si.mediumTransition ? si.mediumInside : medium;
            float toThisArea;
            areaFactors(prev, v, &toThisArea, &v.toPrevArea);
            v.pdfFwd = pdfFwd * toThisArea;
            const Vec3 woLocal = v.woLocal;
            if (++bounces >= maxVertices) break;
            if (woLocal.z == 0) break;
            sampler.seekDimension(block);
            const Vec2 u = sampler.get2D();
            const float uc = bxdf->usesLobeSample() ? sampler.get1D() : 0.5f;
            SurfaceScatter sc;
            if (!scatterAtSurface(v, uc, u, mode, stats, sc)) break;
            scatter *= sc.weight;
            pdfFwd = sc.pdfFwd;
            etaScale *= sc.etaSq;
            const float pdfRev = sc.pdfRev;
            const Vec3 wi = sc.wi;
            prev.pdfRev = pdfRev * v.toPrevArea;
            medium = si.mediumToward(wi, medium);
            ray = spawnRay(si.p, si.ng, wi, ray.time);
        }
        if (scatter.isBlack()) break;
        // Russian roulette on the walk's throughput over its channels' mean density (volpath's).
        const float m = (scatter * etaScale / channelMean(rU, media.spectral)).maxComponent();
        if (m < 1 && bounces > 1 && roulette_) {
            const float q = std::max(0.0f, 1 - m);
            sampler.seekDimension(block + 3);
            if (sampler.get1D() < q) break;
            scatter /= 1 - q;
        }
    }
    return bounces;
}

#define PS_MEDIA_WALK(S)                                                                                       \
    template int Subpaths::randomWalkInMedia<S>(Ray, const Medium*, Spectrum, float, S&, PathStats&,           \
                                                ScratchBuffer&, PathVertex*, int, TransportMode, int,          \
                                                SampledWavelengths*, const MediaSample&, LensHits*) const;
PS_MEDIA_WALK(Sampler)
PS_MEDIA_WALK(PaddedSobolSampler)
PS_MEDIA_WALK(IndependentSampler)
PS_MEDIA_WALK(PrimarySampleSampler)
#undef PS_MEDIA_WALK

}  // namespace ps
