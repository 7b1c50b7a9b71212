// Camera and light subpaths and the vertex queries that connect them (thesis ch. 10):
// random walks that record area-measure densities in both directions, the BSDF seen at a
// vertex (adjoint under importance transport, thesis ch. 5), emitted radiance, the
// densities of light emission, and the geometry term with visibility.
#pragma once
#include "mc/sampler.h"
#include "render/scene.h"
#include "transport/integrator.h"
#include "transport/lens_hits.h"
#include "transport/path_vertex.h"
#include "util/scratch.h"

namespace ps {

// One sample's state for walks and connections in a scene with media: the hero channel
// whose probabilities delta and ratio tracking follow (both subpaths and every connection
// share it: the contribution divides by the channel mean of the whole path's densities,
// media/delta_tracking.h), and a seed from which each walk and each connection draws its own
// numbers, so that a strategy evaluated alone (multiplexed MLT) tracks what it did in the
// whole sample. Null everywhere in scenes without media.
struct MediaSample {
    int hero = 0;
    bool spectral = false;
    const SampledWavelengths* lambda = nullptr;
    uint64_t seed = 0;
    // Rng streams: the camera walk, the light walk, then one per connection.
    static constexpr uint64_t kCameraWalk = 0, kLightWalk = 1, kFirstConnection = 2;
};

class Subpaths {
public:
    Subpaths(const Scene& scene, int maxDepth) : scene_(scene), maxDepth_(maxDepth) {}
    int maxDepth() const { return maxDepth_; }
    // Room a caller must provide: camera subpaths hold the lens vertex and up to maxDepth + 1
    // surface or escape vertices; light subpaths the light vertex and maxDepth surfaces.
    int maxCameraVertices() const { return maxDepth_ + 2; }
    // With lens hits (setLensHits) a light subpath takes one vertex more, so that its last
    // vertex at depth maxDepth scatters too and may reach the lens (t = 0 at every depth).
    int maxLightVertices() const { return maxDepth_ + 1 + (lensHits_ ? 1 : 0); }
    // Whether light walks look for the lens (the t = 0 strategy): their owner passes a
    // LensHits to the walk and connects no more than maxDepth deep.
    void setLensHits(bool on) { lensHits_ = on; }
    bool lensHits() const { return lensHits_; }
    // Russian roulette ends walks early (on by default). A caller that fixes the subpaths'
    // lengths itself (multiplexed Metropolis) turns it off.
    void setRoulette(bool on) { roulette_ = on; }

    // The sample dimensions the walks read, per stream (see Sampler::seekDimension): the
    // camera stream starts with the film and lens position (4 values, drawn by the caller),
    // the light stream with the emission sample (5 values); then every vertex of a walk
    // reads its own block of 4: the direction (2), the lobe choice and Russian roulette.
    // In a scene with media a block has 2 more: the free flight that reached the vertex (its
    // distance and its first collision's choice), so that Metropolis' small steps move
    // medium vertices a little too.
    static constexpr int kCameraStartDimensions = 4, kLightStartDimensions = 5, kDimensionsPerVertex = 4;
    static constexpr int kDimensionsPerMediaVertex = 6;
    int dimensionsPerVertex() const { return scene_.hasMedia() ? kDimensionsPerMediaVertex : kDimensionsPerVertex; }
    // Streamed samplers (Metropolis) read the path's time (motion blur) in the camera stream
    // just past the last vertex block a camera walk can read.
    int timeDimension() const { return kCameraStartDimensions + dimensionsPerVertex() * maxCameraVertices(); }

    // Vertex 0 on the lens, then the walk along `ray`, which the scene camera generated;
    // returns the number of vertices. The walks are compiled for the renderer's samplers
    // (S: Sampler, PaddedSobolSampler or IndependentSampler) so that hot loops call them
    // without virtual dispatch.
    // maxVertices (> 0) stops the walk earlier than maxCameraVertices().
    // `lambda`, in spectral mode (null: RGB), the path's wavelengths: both subpaths of a
    // sample share them, every scene spectrum is evaluated at them, and a dispersive
    // surface on either walk terminates the secondary ones for the whole sample.
    // `media`: this sample's MediaSample in a scene with media (mediaSample()), else null.
    template <typename S>
    int cameraSubpath(const Ray& ray, S& sampler, ScratchBuffer& scratch, PathStats& stats, PathVertex* path,
                      int maxVertices = 0, SampledWavelengths* lambda = nullptr,
                      const MediaSample* media = nullptr) const;
    // Vertex 0 on a light chosen as light subpaths choose (Scene::sampleLight), then the walk;
    // returns the number of vertices.
    // `time`: the scene time of the whole path (the camera sample's, for BDPT).
    // `lens` (non-null, thin lens): the rays that cross the lens are recorded there (lens_hits.h,
    // the t = 0 strategy); in media, those whose free flight passes the lens.
    template <typename S>
    int lightSubpath(S& sampler, float time, ScratchBuffer& scratch, PathStats& stats, PathVertex* path,
                     SampledWavelengths* lambda = nullptr, const MediaSample* media = nullptr,
                     LensHits* lens = nullptr) const;
    // lightSubpath in two steps: the emitted ray (vertex 0 written to path[0]), then the walk.
    // BDPT samples the origin before tracing its camera subpath, so that the emission
    // sampling's latency overlaps that walk (only the order of sample dimensions changes).
    struct LightOrigin {
        bool valid = false;  // false: no light subpath (no light, or nothing emitted)
        Ray ray;             // the first ray, offset from the light's surface
        Vec3 direction;      // its unit direction
        Spectrum beta;       // throughput after the first segment's emission factors
        float pdfPos = 0, pdfDir = 0;  // sampleLe's densities
        const Medium* medium = nullptr;  // where the first ray starts (scenes with media)
    };
    template <typename S>
    LightOrigin lightOrigin(S& sampler, float time, PathStats& stats, PathVertex* path,
                            const SampledWavelengths* lambda = nullptr) const;
    template <typename S>
    int continueLightSubpath(const LightOrigin& origin, S& sampler, ScratchBuffer& scratch, PathStats& stats,
                             PathVertex* path, int maxVertices = 0, SampledWavelengths* lambda = nullptr,
                             const MediaSample* media = nullptr, LensHits* lens = nullptr) const;
    // A scene with media: draws the sample's hero (RGB mode; spectral mode's is lambda[0]) and
    // seed from the camera stream, past every value the camera walk, the time and the wavelengths read.
    template <typename S>
    MediaSample mediaSample(S& sampler, const SampledWavelengths* lambda) const;
    // Whether a connection from a (in its medium towards b) to b carries light: visibility,
    // or with media (media non-null) the ratio-tracking transmittance, which multiplies L
    // divided by the channel mean of the path's density ratios (rU: its subpaths', times the
    // tracking's). `stream`: the connection's Rng stream (MediaSample).
    bool connectThrough(const PathVertex& a, const PathVertex& b, const Spectrum& rU, PathStats& stats,
                        const MediaSample* media, uint64_t stream, Spectrum& L) const;

    // The BSDF at surface vertex v for light between v.wo and the direction to `next`,
    // including the adjoint shading-normal factor under importance transport.
    Spectrum f(const PathVertex& v, const PathVertex& next, TransportMode mode) const;
    // Surface vertex v of a walk (bxdf set) seen along unit direction w: f as f() gives it for
    // v's own mode, the solid-angle density of sampling w (pdfFwd) and of sampling back
    // towards v's previous vertex from w (pdfRev), in one BxDF call; and |w.ns|, if asked.
    BxDFEval evaluate(const PathVertex& v, Vec3 w, float* absCosShading = nullptr) const;
    // Area density at `next` of sampling it from v (prev: the vertex before v in the
    // direction of sampling). `reverse` when sampling against v's own subpath, which uses
    // the adjoint BSDF's density.
    float pdf(const PathVertex& v, const PathVertex* prev, const PathVertex& next, bool reverse) const;
    // Area density of a light subpath starting at emitter vertex v (towards `to`),
    // including the choice of the light.
    float pdfLightOrigin(const PathVertex& v, const PathVertex& to) const;
    // Area density at `to` of the direction a light subpath from v would sample.
    float pdfLight(const PathVertex& v, const PathVertex& to) const;
    // Both of the above from one emission query (a connection to a sampled light needs
    // both); either pointer may be null.
    void emissionDensities(const PathVertex& v, const PathVertex& to, float* origin, float* next) const;
    // Radiance emitted at light vertex v towards `to` (at lambda in spectral mode).
    Spectrum Le(const PathVertex& v, const PathVertex& to, const SampledWavelengths* lambda = nullptr) const;
    // Mutual visibility of two points, at a's time (a path's vertices share one time).
    bool visible(const PathVertex& a, const PathVertex& b, PathStats& stats) const;
    // Density of choosing direction wToLight from all infinite lights together.
    float infiniteLightDensity(Vec3 wToLight) const;
    // Next-event estimation (s = 1) chooses the light of emitter vertex y0 for the point y1
    // (the scene's light sampler); light subpaths by Scene::sampleLight, and the origin
    // densities (pdfLightOrigin) say so. This is the ratio of the first choice's probability
    // to the second's: the factor by which the s = 1 strategy's density of a path differs from
    // the one its light vertex's origin density gives (0: s = 1 cannot choose this light).
    float lightChoiceRatio(const PathVertex& y0, const PathVertex& y1) const;

    const Scene& scene() const { return scene_; }

private:
    template <typename S>
    int randomWalk(Ray ray, Spectrum beta, float pdfDir, S& sampler, ScratchBuffer& scratch, PathStats& stats,
                   PathVertex* path, int maxVertices, TransportMode mode, int firstDimension,
                   SampledWavelengths* lambda, LensHits* lens = nullptr) const;
    // randomWalk in a scene with media (subpaths_media.cpp): free flights by delta tracking
    // from `medium`, medium vertices, medium changes at boundaries; lens crossings that the
    // flights pass (light walks, `lens` non-null).
    template <typename S>
    int randomWalkInMedia(Ray ray, const Medium* medium, Spectrum beta, float pdfDir, S& sampler, PathStats& stats,
                          ScratchBuffer& scratch, PathVertex* path, int maxVertices, TransportMode mode,
                          int firstDimension, SampledWavelengths* lambda, const MediaSample& media,
                          LensHits* lens = nullptr) const;

    const Scene& scene_;
    int maxDepth_;
    bool roulette_ = true;
    bool lensHits_ = false;
};

// The adjoint BSDF's shading-normal factor (thesis §5.3, the adjoint of a BSDF with
// shading normals): a particle arriving from wo and leaving along wi carries
// f_s(wo, wi) |wo.Ns| |wi.Ng| / (|wo.Ng| |wi.Ns|) in place of f_s, so that light tracing
// with shading cosines |wi.Ns| estimates the same measurement as path tracing.
inline float adjointShadingFactor(Vec3 wo, Vec3 wi, Vec3 ns, Vec3 ng) {
    float denom = std::fabs(dot(wo, ng)) * std::fabs(dot(wi, ns));
    if (!(denom > 0)) return 0;
    return std::fabs(dot(wo, ns)) * std::fabs(dot(wi, ng)) / denom;
}

// A walk's surface vertex at si (fresh: resetVertex), but for its throughput and densities.
inline void initSurfaceVertex(PathVertex& v, const SurfaceInteraction& si, const BxDF* bxdf, TransportMode mode,
                              float time) {
    v.kind = VertexKind::Surface;
    v.mode = mode;
    v.p = si.p;
    v.time = time;
    v.ng = si.ng;
    v.ns = si.ns;
    v.wo = si.wo;
    v.uv = si.uv;
    v.frame = si.shadingFrame();
    v.bxdf = bxdf;
    v.nonSpecular = (bxdf->flags() & (kDiffuse | kGlossy)) != 0;
    v.facesRay = si.fibre == FibreKind::FacingRay;
    // On a strip facing each ray (flat and cylinder curves) the factor's geometric cosines
    // would be the strip's, which turns with the ray that met it: the hair BSDF's adjoint
    // makes the same correction with the fibre's projected widths (hair_bxdf.cpp).
    v.flatShading = si.ns == si.ng || v.facesRay;
    v.light = si.areaLight;
    v.woLocal = v.frame.toLocal(si.wo);
}

// Where a camera walk's ray (unit direction) escaped to the infinite lights (s = 0 only).
inline void initEscapeVertex(PathVertex& v, const Ray& ray, const Spectrum& beta, float pdfFwd) {
    resetVertex(v);
    v.kind = VertexKind::Light;
    v.mode = TransportMode::Radiance;
    v.infinite = true;
    v.time = ray.time;
    v.p = ray.o + ray.d;
    v.wo = -ray.d;
    v.beta = beta;
    v.pdfFwd = pdfFwd;
}

// The BSDF sampling that continues a walk from surface vertex v (initSurfaceVertex'd): the
// direction, the throughput weight f |cos| / pdf (adjoint under importance transport) and the
// solid-angle densities forward and reverse; a delta lobe marks v. False: the walk ends.
struct SurfaceScatter {
    Vec3 wi;
    Spectrum weight;
    float pdfFwd = 0, pdfRev = 0;
    float etaSq = 1;  // radiance through a refraction: eta^2, undone for Russian roulette
};
inline bool scatterAtSurface(PathVertex& v, float uc, Vec2 u, TransportMode mode, PathStats& stats, SurfaceScatter& sc) {
    const auto bs = v.bxdf->sample(v.woLocal, uc, u, mode);
    if (!bs || !(bs->pdf > 0) || bs->f.isBlack()) return false;
    sc.wi = v.frame.toWorld(bs->wi);
    sc.weight = bs->f * (absCosTheta(bs->wi) / bs->pdf);
    if (mode == TransportMode::Importance && !v.flatShading) sc.weight *= adjointShadingFactor(v.wo, sc.wi, v.ns, v.ng);
    if (!sc.weight.isFinite()) {
        ++stats.guarded;
        return false;
    }
    // Layered BxDFs only know their pdf up to a factor; MIS needs the true density.
    sc.pdfFwd = bs->pdfIsProportional ? v.bxdf->pdf(v.woLocal, bs->wi, mode) : bs->pdf;
    sc.pdfRev = v.bxdf->pdf(bs->wi, v.woLocal, adjoint(mode));
    if (bs->isSpecular()) {
        // Delta lobes: no strategy connects to this vertex, and in the MIS ratios (thesis
        // §10.3.5) the delta density of a scattering direction and that of its reverse
        // cancel. They stand in as a unit density per solid angle, so the neighbours'
        // area densities keep their geometric factors cos / d^2: dropping those (a zero
        // density remapped to 1, as pbrt-v4 does) misweights strategies through specular
        // chains, e.g. 4.9x the variance of the weights kept here for a light inside glass.
        v.delta = true;
        sc.pdfFwd = sc.pdfRev = 1;
    }
    sc.etaSq = mode == TransportMode::Radiance && bs->isTransmission() ? sqr(bs->eta) : 1.0f;
    return true;
}

// Inline: called for most connections, from BDPT's translation unit.
inline BxDFEval Subpaths::evaluate(const PathVertex& v, Vec3 w, float* absCosShading) const {
    Vec3 wLocal = v.frame.toLocal(w);
    if (absCosShading) *absCosShading = std::fabs(wLocal.z);
    BxDFEval e = v.bxdf->evaluate(v.woLocal, wLocal, v.mode);
    // With ns == ng the factor is 1, or 0 only where a cosine the caller multiplies by is 0.
    if (v.mode == TransportMode::Importance && !v.flatShading) e.f *= adjointShadingFactor(v.wo, w, v.ns, v.ng);
    return e;
}

}  // namespace ps
