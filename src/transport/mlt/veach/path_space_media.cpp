// Veach's path space with participating media (issue 36; Pauly, Kollig and Keller 2000,
// "Metropolis light transport for participating media"): a vertex may be a scattering point
// in a medium, whose measure is volume (no cosine at it; the geometry term keeps 1 / d^2),
// whose "BSDF" is sigma_s times the phase function, and every edge carries its
// transmittance.
//
// Why the free flights follow the majorant alone. A mutation's T(x -> y) must be a
// deterministic function of the paths, but delta tracking's density of a scattering at
// distance t, sigma(t) exp(-integral of sigma), has no closed form in a grid medium. So a
// new vertex is the first point of the Poisson process of the medium's majorant (the
// largest channel's, piecewise constant along a ray: exact integrals): a medium vertex at
// t has density mu(t) exp(-integral of mu over [0, t]), a surface reached through the
// medium exp(-integral over the edge). Points where sigma_s is small get small f and are
// rejected more often; that costs efficiency, not correctness.
//
// Why f may be random. Transmittance in a grid medium is estimated by ratio tracking
// against the same majorant: unbiased and non-negative per channel. The chain is then a
// pseudo-marginal one (Andrieu and Roberts 2009): each state keeps the estimate it was
// accepted with (veach_mlt.cpp's PathState::C) and proposals draw fresh ones, which leaves
// the chain exact for the marginal target f (and b, the mean of the estimates, unchanged).
// In a homogeneous medium the transmittance is exp(-sigma_t d), exact and deterministic.
#include <cmath>
#include <limits>

#include "media/homogeneous_medium.h"
#include "transport/mlt/veach/path_space.h"

namespace ps {

namespace {

const SampledWavelengths* wavelengthsOfPath(const MltVertex& v) { return v.lambda.lambda[0] > 0 ? &v.lambda : nullptr; }

// The majorant the flights sample: the largest channel's of a segment (one for all, so
// the density is one number).
float scalarMajorant(const MajorantSegment& seg) { return std::max(0.0f, seg.sigmaMaj.maxComponent()); }

}  // namespace

template <typename Part>
bool PathSpace::alongEdge(const MltVertex& a, const MltVertex& b, PathStats* stats, Part&& part) const {
    const bool reversed = atInfinity(a);
    const MltVertex& start = reversed ? b : a;
    const MltVertex& end = reversed ? a : b;
    const Vec3 w = directionTo(start, end);
    const bool finite = !atInfinity(end);
    const Vec3 target = finite ? end.p : Vec3();
    const Medium* medium = mediumFrom(start, w);
    Vec3 from = start.p, fromNg = start.kind == MltVertex::Kind::Lens ? Vec3() : start.ng;
    for (int crossings = 0; crossings < 1024; ++crossings) {
        const Ray ray = finite ? shadowRay(from, fromNg, end, start.time) : spawnRay(from, fromNg, w, start.time);
        SurfaceInteraction si;
        if (stats) ++stats->rays;
        const bool hit = ray.tMax > 0 && scene_.intersect(ray, si);
        if (hit && si.material && !si.material->isInterface()) return false;
        if (medium) {
            const float len = hit ? si.t * length(ray.d)
                              : finite ? length(target - ray.o) : std::numeric_limits<float>::infinity();
            if (!part(*medium, ray.o, w, len)) return true;  // the part ended the walk (a zero estimate)
        }
        if (!hit) return true;
        medium = si.mediumToward(w, medium);
        from = si.p;
        fromNg = si.ng;
    }
    return false;
}

bool PathSpace::sampleFlight(const Medium& medium, const Ray& ray, float tEnd, const SampledWavelengths& lambda,
                             Rng& rng, Vec3* p) {
    const float len = length(ray.d);
    if (!(len > 0)) return false;
    const Vec3 d = ray.d / len;
    MajorantIterator segments = medium.majorants(ray.o, d, tEnd * len, lambda.lambda[0] > 0 ? &lambda : nullptr);
    MajorantSegment seg;
    while (segments.next(&seg)) {
        const float mu = scalarMajorant(seg);
        if (!(mu > 0)) continue;
        // Memoryless: a flight past a segment's end restarts in the next one.
        const float t = seg.t0 - std::log(1 - rng.uniform()) / mu;
        if (t < seg.t1) {
            *p = ray.o + d * t;
            return true;
        }
    }
    return false;
}

bool PathSpace::traceInMedium(const Ray& ray, float tEnd, const Medium& medium, const SampledWavelengths& lambda,
                              Rng& rng, MltVertex& out) const {
    Vec3 p;
    if (!sampleFlight(medium, ray, tEnd, lambda, rng, &p)) return false;
    out = MltVertex();
    out.kind = MltVertex::Kind::Medium;
    out.p = p;  // ng, ns zero: a point (no cosine, no ray offset)
    out.mediumAbove = out.mediumBelow = &medium;
    out.time = ray.time;
    out.lambda = lambda;
    return true;
}

bool PathSpace::scatterInMedium(std::vector<MltVertex>& side, Rng& rng, Ray& ray) const {
    const MltVertex& v = side.back();
    float pdf = 0;
    const Vec2 u(rng.uniform(), rng.uniform());
    // HG samples its own value (p / pdf = 1), towards the previous vertex as wo.
    const Vec3 wi = v.mediumAbove->phase().sample(directionTo(v, side[side.size() - 2]), u, &pdf);
    if (!(pdf > 0)) return false;
    ray = Ray{v.p, wi, std::numeric_limits<float>::infinity(), v.time};
    return true;
}

bool PathSpace::visibleThroughMedia(const MltVertex& a, const MltVertex& b, PathStats& stats) const {
    return alongEdge(a, b, &stats, [](const Medium&, Vec3, Vec3, float) { return true; });
}

const Medium* PathSpace::mediumFrom(const MltVertex& v, Vec3 w) const {
    if (!scene_.hasMedia()) return nullptr;
    if (v.kind == MltVertex::Kind::Lens) return scene_.cameraMedium();
    if (v.kind == MltVertex::Kind::Light) return atInfinity(v) ? nullptr : v.light->mediumToward(v.ng, w);
    return v.mediumToward(w);
}

double PathSpace::flightDensity(const MltVertex& a, const MltVertex& b) const {
    if (!scene_.hasMedia()) return 1;
    const SampledWavelengths* lambda = wavelengthsOfPath(a);
    double depth = 0;
    const bool open = alongEdge(a, b, nullptr, [&](const Medium& m, Vec3 o, Vec3 w, float len) {
        MajorantIterator segments = m.majorants(o, w, len, lambda);
        MajorantSegment seg;
        while (segments.next(&seg))
            if (const float mu = scalarMajorant(seg); mu > 0) depth += double(mu) * double(seg.t1 - seg.t0);
        return true;
    });
    if (!open || !std::isfinite(depth)) return 0;
    double p = std::exp(-depth);
    if (b.isMedium()) {
        // The majorant at b, in the cell b lies in (along the edge's direction past b).
        MajorantIterator segments = b.mediumAbove->majorants(b.p, directionTo(a, b), 1e-4f * (1 + length(b.p)), lambda);
        MajorantSegment seg;
        p *= segments.next(&seg) && seg.t0 <= 0 ? double(scalarMajorant(seg)) : 0.0;
    }
    return p;
}

Spectrum PathSpace::edgeTransmittance(const MltVertex& a, const MltVertex& b, Rng* rng, PathStats* stats) const {
    const SampledWavelengths* lambda = wavelengthsOfPath(a);
    Spectrum T(1.0f);
    Rng fallback(0x9e3779b97f4a7c15ULL);
    Rng& r = rng ? *rng : fallback;
    const bool open = alongEdge(a, b, stats, [&](const Medium& m, Vec3 o, Vec3 w, float end) {
        if (dynamic_cast<const HomogeneousMedium*>(&m)) {
            const MediumProperties mp = m.at(o, lambda);
            const Spectrum sigmaT = mp.sigmaA + mp.sigmaS;
            for (int c = 0; c < 4; ++c)  // an unbounded edge leaves a channel with sigma_t = 0 alone
                if (sigmaT[c] > 0) T[c] *= std::exp(-sigmaT[c] * end);
            return !T.isBlack();
        }
        // Ratio tracking (Novak et al. 2014) against the flights' majorant.
        MajorantIterator segments = m.majorants(o, w, end, lambda);
        MajorantSegment seg;
        while (segments.next(&seg)) {
            const float mu = scalarMajorant(seg);
            if (!(mu > 0)) continue;
            for (float t = seg.t0;;) {
                t -= std::log(1 - r.uniform()) / mu;
                if (!(t < seg.t1)) break;
                const MediumProperties mp = m.at(o + w * t, lambda);
                T *= clampZero(Spectrum(1.0f) - (mp.sigmaA + mp.sigmaS) / mu);
                if (T.isBlack()) return false;
            }
        }
        return true;
    });
    return open && T.isFinite() ? T : Spectrum();
}

}  // namespace ps
