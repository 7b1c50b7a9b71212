#include "transport/bdpt.h"

#include <algorithm>
#include <new>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace ps {

namespace {

// Whether strategy (s, t) uses a dispersive vertex (s = 1 and t = 1 sample their own
// endpoint, which is not a surface vertex of the subpaths).
bool usesDispersiveVertex(const PathVertex* light, const PathVertex* camera, int s, int t) {
    for (int i = 1; i < s; ++i)
        if (light[i].dispersive) return true;
    for (int i = 1; i < t; ++i)
        if (camera[i].dispersive) return true;
    return false;
}

}  // namespace

template <typename S>
BDPTIntegrator::Connection BDPTIntegrator::connect(PathVertex* light, PathVertex* camera, int s, int t, S& sampler,
                                                   PathStats& stats, bool weighted, const MisPrefixes* prefixes,
                                                   const SampleContext* splatTo,
                                                   const SampledWavelengths* lambda,
                                                   const MediaSample* media) const {
    Join j;  // filled in place: it holds a whole vertex
    Connection c;
    if (splatTo) lambda = splatTo->lambda;
    const uint64_t stream = media ? MediaSample::kFirstConnection + uint64_t(connectionDimension(s, t)) : 0;
    const ShadowRoulette* roulette = splatTo && splatTo->roulette.active() && !media ? &splatTo->roulette : nullptr;
    j.deferVisibility = roulette != nullptr;
    if (s == 0) {
        joinEmitter(camera, t, lambda, media, j);
    } else if (t > 1 && camera[t - 1].isInfiniteLight()) {
        return c;  // an escaped camera ray is an endpoint only for s = 0
    } else if (t == 1) {
        joinLens(light[s - 1], sampler, stats, splatTo, media, stream, j);
        c.pRaster = j.pRaster;
    } else if (s == 1) {
        joinLight(camera[t - 1], sampler, stats, lambda, media, stream, j);
    } else {
        joinInner(light[s - 1], camera[t - 1], stats, media, stream, j);
    }
    if (j.L.isBlack()) return c;
    if (!j.L.isFinite()) {
        ++stats.guarded;
        return c;
    }
    c.L = j.L;
    const PathVertex* sampled = j.sampled ? &*j.sampled : nullptr;
    c.weight = weighted ? misWeight(light, camera, sampled, s, t, j.haveKnown ? &j.known : nullptr, prefixes) : 1.0f;
    if (recomputeWeights_) c.recomputedWeight = misWeight(light, camera, sampled, s, t, nullptr);
    if (j.from) {
        // Shadow-ray roulette on the contribution as the film will take it (produce divides
        // the paths only light subpaths sample by the light path share).
        float scale;
        if (!roulette->trace(c.L * (c.weight * lightSubpathScale(light, s, t)), uint64_t(connectionDimension(s, t)),
                             &scale)) {
            ++stats.shadowRaysSkipped;
            c.L = Spectrum();
            return c;
        }
        if (!paths_.visible(*j.from, *j.to, stats)) {
            c.L = Spectrum();
            return c;
        }
        c.L *= scale;
    }
    return c;
}

// The camera subpath found an emitter on its own (s = 0).
void BDPTIntegrator::joinEmitter(const PathVertex* camera, int t, const SampledWavelengths* lambda,
                                 const MediaSample* media, Join& j) const {
    const PathVertex& pt = camera[t - 1];
    if (pt.isLight()) j.L = paths_.Le(pt, camera[t - 2], lambda) * pt.beta;
    if (media) j.L /= channelMean(pt.rU, media->spectral);  // spectral MIS (subpaths_media.cpp)
}

// Connect light vertex qs to a sampled lens point, to be splatted (t = 1, thesis §10.2).
template <typename S>
void BDPTIntegrator::joinLens(const PathVertex& qs, S& sampler, PathStats& stats, const SampleContext* splatTo,
                              const MediaSample* media, uint64_t stream, Join& j) const {
    if (!qs.connectible()) return;
    auto cs = paths_.scene().camera().sampleWi(qs.p, qs.time, sampler.get2D());
    if (!cs) return;
    PathVertex& lens = j.sampled.emplace();
    lens.kind = VertexKind::Camera;
    lens.mode = TransportMode::Radiance;
    lens.p = cs->pLens;
    lens.time = qs.time;
    lens.beta = Spectrum(cs->We / cs->pdf);
    j.pRaster = cs->pRaster;
    if (qs.kind == VertexKind::Surface && qs.bxdf) {
        float cosQs;
        BxDFEval e = paths_.evaluate(qs, cs->wi, &cosQs);
        j.L = qs.beta * e.f * lens.beta * cosQs;
        float toLens, toQs;
        areaFactors(qs, lens, &toLens, &toQs);
        j.known.pt = e.pdfFwd * toLens;
        j.known.qs = cs->pdfDir * toQs;
        j.known.qsMinus = e.pdfRev * qs.toPrevArea;
        j.haveKnown = true;
    } else {
        j.L = qs.beta * paths_.f(qs, lens, TransportMode::Importance) * lens.beta;
        if (qs.onSurface()) j.L *= std::fabs(dot(cs->wi, qs.ns));
    }
    if (!j.L.isBlack()) {
        if (splatTo) splatTo->film.prefetchSplat(j.pRaster, splatTo->sampleIndex);
        const bool through = media ? paths_.connectThrough(qs, lens, qs.rU, stats, media, stream, j.L)
                                   : j.visibleNowOrLater(qs, lens, paths_, stats);
        if (!through) j.L = Spectrum();
    }
}

// Next-event estimation (s = 1): a light point sampled as seen from camera vertex pt.
template <typename S>
void BDPTIntegrator::joinLight(const PathVertex& pt, S& sampler, PathStats& stats, const SampledWavelengths* lambda,
                               const MediaSample* media, uint64_t stream, Join& j) const {
    if (!pt.connectible()) return;
    // The light is chosen for pt (the scene's light sampler); the weights know the choice
    // through Subpaths::lightChoiceRatio, since the vertex's origin density is the
    // light subpaths' choice (Scene::lightPmf).
    const LightSampleContext ctx{pt.p, pt.ng, lambda};
    const SampledLight sl = paths_.scene().lightSampler().sample(ctx, sampler.get1D());
    const Light* lt = sl.light;
    const float pmf = sl.pmf;
    Vec2 u = sampler.get2D();
    if (!lt || !(pmf > 0)) return;
    auto ls = lt->sampleLi(ctx, u);
    if (!ls || ls->L.isBlack() || !(ls->pdf > 0)) return;
    const float emissionPmf = paths_.scene().lightPmf(lt);
    PathVertex& lv = j.sampled.emplace();
    lv.kind = VertexKind::Light;
    lv.mode = TransportMode::Importance;
    lv.light = lt;
    lv.infinite = lt->atInfinity();
    lv.p = ls->pLight;
    lv.ng = lv.ns = ls->nLight;
    lv.beta = ls->L / (ls->pdf * pmf);
    if (pt.kind == VertexKind::Surface && pt.bxdf) {
        float cosPt;
        BxDFEval e = paths_.evaluate(pt, ls->wi, &cosPt);
        j.L = pt.beta * e.f * lv.beta * cosPt;
        if (ls->pdfEmitPos > 0) {
            // The light gave its emission densities; only their conversions to area remain.
            float toPt, toLight;
            areaFactors(lv, pt, &toPt, &toLight);
            lv.pdfFwd = emissionPmf * ls->pdfEmitPos;
            j.known.pt = ls->pdfEmitDir * toPt;
            j.known.qs = e.pdfFwd * toLight;
        } else {
            paths_.emissionDensities(lv, pt, &lv.pdfFwd, &j.known.pt);
            j.known.qs = e.pdfFwd * areaFactor(pt, lv);
        }
        j.known.ptMinus = e.pdfRev * pt.toPrevArea;
        // Lights at infinity share the vertex: the ratio is over all of them.
        if (!lv.infinite) j.known.lightChoice = emissionPmf > 0 ? pmf / emissionPmf : 0.0f;
        j.haveKnown = true;
    } else {
        lv.pdfFwd = paths_.pdfLightOrigin(lv, pt);
        j.L = pt.beta * paths_.f(pt, lv, TransportMode::Radiance) * lv.beta;
        if (pt.onSurface()) j.L *= std::fabs(dot(ls->wi, pt.ns));
    }
    if (j.L.isBlack()) return;
    const bool through = media ? paths_.connectThrough(pt, lv, pt.rU, stats, media, stream, j.L)
                               : j.visibleNowOrLater(pt, lv, paths_, stats);
    if (!through) j.L = Spectrum();
}

// Both subpaths contribute a vertex (s, t > 1); join them deterministically. One direction
// serves both BSDFs, the geometry term and the four densities the weight needs.
void BDPTIntegrator::joinInner(const PathVertex& qs, const PathVertex& pt, PathStats& stats, const MediaSample* media,
                               uint64_t stream, Join& j) const {
    if (!qs.connectible() || !pt.connectible()) return;
    if (media) return joinInnerInMedia(qs, pt, stats, *media, stream, j);
    Vec3 d = pt.p - qs.p;
    float d2 = lengthSquared(d);
    if (!(d2 > 0)) return;
    float invDist2 = 1 / d2;
    Vec3 w = d * std::sqrt(invDist2);  // from qs towards pt
    float cosQs, cosPt;
    BxDFEval atQs = paths_.evaluate(qs, w, &cosQs);
    if (atQs.f.isBlack()) return;  // often: w leaves qs on the wrong side
    BxDFEval atPt = paths_.evaluate(pt, -w, &cosPt);
    float g = cosQs * cosPt * invDist2;
    j.L = qs.beta * atQs.f * atPt.f * pt.beta * g;
    if (j.L.isBlack() || !j.visibleNowOrLater(qs, pt, paths_, stats)) {
        j.L = Spectrum();
        return;
    }
    j.known.pt = atQs.pdfFwd * densityCos(pt, w) * invDist2;
    j.known.qs = atPt.pdfFwd * densityCos(qs, w) * invDist2;
    j.known.ptMinus = atPt.pdfRev * pt.toPrevArea;
    j.known.qsMinus = atQs.pdfRev * qs.toPrevArea;
    j.haveKnown = true;
}

void BDPTIntegrator::joinInnerInMedia(const PathVertex& qs, const PathVertex& pt, PathStats& stats,
                                      const MediaSample& media, uint64_t stream, Join& j) const {
    const Vec3 d = pt.p - qs.p;
    const float d2 = lengthSquared(d);
    if (!(d2 > 0)) return;
    const Vec3 w = d / std::sqrt(d2);
    // No cosine at a medium vertex: G = 1 / d^2 there (thesis eq. 8.4 in volume measure).
    const float cosQs = qs.onSurface() ? std::fabs(dot(w, qs.ns)) : 1.0f;
    const float cosPt = pt.onSurface() ? std::fabs(dot(w, pt.ns)) : 1.0f;
    j.L = qs.beta * paths_.f(qs, pt, TransportMode::Importance) * paths_.f(pt, qs, TransportMode::Radiance) * pt.beta *
          (cosQs * cosPt / d2);
    if (j.L.isBlack() || !paths_.connectThrough(qs, pt, qs.rU * pt.rU, stats, &media, stream, j.L)) j.L = Spectrum();
}

namespace {

// Room for n subpath vertices in scratch. No construction: the walks assign every vertex
// they report (PathVertex is an aggregate, so the storage holds implicitly created
// vertices), and nothing reads beyond.
PathVertex* allocPath(ScratchBuffer& scratch, int n) {
    return static_cast<PathVertex*>(scratch.allocBytes(sizeof(PathVertex) * size_t(n), alignof(PathVertex)));
}

// Delta densities are stored as 0; they cancel in the ratios (remapped to 1), and the
// strategies that would need to sample a delta vertex by connection are excluded.
inline float remapDelta(float f) { return f != 0 ? f : 1.0f; }

// Another strategy's weight relative to this one's, from the ratio r of their densities
// (uniform: each strategy counts once). For all three heuristics the term of a product is
// the product of the terms (1 = 1 x 1 for uniform), so sums along a path factor. The
// heuristic is a template parameter: weights are the innermost loop of BDPT.
template <MisHeuristic H>
double misTerm(float pdfRev, float pdfFwd) {
    if constexpr (H == MisHeuristic::Uniform) return 1.0;
    double r = double(remapDelta(pdfRev)) / remapDelta(pdfFwd);
    if constexpr (H == MisHeuristic::Power) return r * r;
    return r;
}

// One step of the running sums (see MisPrefixes): vertex m's exchanged density ratio times
// (whether a connection could sample vertex m, plus the sum up to m - 1).
template <MisHeuristic H>
double cameraPrefixStep(const PathVertex* camera, int m, double before) {
    bool valid = !camera[m].delta && !camera[m - 1].delta;
    return misTerm<H>(camera[m].pdfRev, camera[m].pdfFwd) * ((valid ? 1 : 0) + before);
}
// The term of a factor k of a density ratio: the s = 1 strategy's light choice
// (Subpaths::lightChoiceRatio), which its density ratio to any other strategy carries.
template <MisHeuristic H>
double choiceTerm(float k) {
    if constexpr (H == MisHeuristic::Uniform) return k > 0 ? 1.0 : 0.0;
    if constexpr (H == MisHeuristic::Power) return double(k) * k;
    return k;
}
// At m = 1 the strategy counted is s = 1, whose term carries its light choice (choice).
template <MisHeuristic H>
double lightPrefixStep(const PathVertex* light, int m, double before, float choice) {
    bool valid = !light[m].delta && !(m > 0 ? light[m - 1].delta : light[0].isDeltaLight());
    const double own = m == 1 ? choiceTerm<H>(choice) : 1.0;
    return misTerm<H>(light[m].pdfRev, light[m].pdfFwd) * ((valid ? own : 0) + before);
}

// The term of the t = 0 strategy's density ratio (BDPTIntegrator::lensRatio; 0: no such
// strategy).
template <MisHeuristic H>
double lensTerm(float ratio) {
    return ratio > 0 ? misTerm<H>(ratio, 1.0f) : 0.0;
}

// Calls f with the heuristic as a compile-time constant.
template <typename F>
auto withHeuristic(MisHeuristic h, F&& f) {
    switch (h) {
        case MisHeuristic::Balance: return f(std::integral_constant<MisHeuristic, MisHeuristic::Balance>{});
        case MisHeuristic::Uniform: return f(std::integral_constant<MisHeuristic, MisHeuristic::Uniform>{});
        case MisHeuristic::Power:
        case MisHeuristic::Cutoff:
        case MisHeuristic::Maximum: break;  // general_: never on this path
    }
    return f(std::integral_constant<MisHeuristic, MisHeuristic::Power>{});
}

}  // namespace

BDPTIntegrator::BDPTIntegrator(const Scene& scene, int maxDepth, MisWeighting mis)
    : paths_(scene, maxDepth), mis_(mis), heuristic_(mis.heuristic) {
    // Light walks reach a thin lens, in media too (their flights must pass it: subpaths_media.cpp).
    lensHits_ = scene.camera().hasLensDisk();
    paths_.setLensHits(lensHits_);
    // The default (power, beta 2), balance and uniform keep the prefix sums' O(1) weights.
    general_ = !(mis.isDefault() || mis.heuristic == MisHeuristic::Balance || mis.heuristic == MisHeuristic::Uniform);
    if (general_) heuristic_ = MisHeuristic::Balance;  // its prefixes are computed, unused
}

BDPTIntegrator::MisPrefixes BDPTIntegrator::misPrefixes(const PathVertex* light, int nLight, const PathVertex* camera,
                                                        int nCamera, ScratchBuffer& scratch) const {
    auto* cam = static_cast<double*>(scratch.allocBytes(sizeof(double) * size_t(std::max(nCamera, 1)), alignof(double)));
    auto* lig = static_cast<double*>(scratch.allocBytes(sizeof(double) * size_t(std::max(nLight, 1)), alignof(double)));
    // The s = 1 strategy's light choice for this light subpath's first two vertices (unused
    // when the second is specular: s = 1 cannot connect to it).
    const float choice = nLight >= 2 && !light[1].delta ? paths_.lightChoiceRatio(light[0], light[1]) : 1.0f;
    withHeuristic(heuristic_, [&](auto h) {
        constexpr MisHeuristic H = decltype(h)::value;
        // The t = 0 strategy (the light subpath reaching the lens) ends every camera-side sum.
        cam[0] = nCamera >= 2 ? lensTerm<H>(lensRatio(camera[0].pdfRev, camera[0], camera[1])) : 0.0;
        for (int m = 1; m <= nCamera - 2; ++m) cam[m] = cameraPrefixStep<H>(camera, m, cam[m - 1]);
        for (int m = 0; m <= nLight - 2; ++m) lig[m] = lightPrefixStep<H>(light, m, m > 0 ? lig[m - 1] : 0.0, choice);
    });
    return {cam, lig, choice};
}

// The weight of strategy (s, t) relative to every other strategy (s', t') with s' + t' = s + t
// that could have produced the same path (thesis §10.2.3, eq. 10.9): the ratio of each
// other strategy's density to this one's follows from walking along the path and
// exchanging one vertex's forward density for its reverse density at a time.
float BDPTIntegrator::misWeight(const PathVertex* light, const PathVertex* camera, const PathVertex* sampled, int s,
                                int t, const EndpointDensities* known, const MisPrefixes* prefixes) const {
    if (s + t == 2) return 1;
    // The path as the connection made it: the sampled vertex stands in for light[0] (s = 1)
    // or camera[0] (t = 1), and the four vertices at the join get the reverse densities of
    // the other side's walk. Nothing is written back into the subpaths.
    const PathVertex* qs = s > 0 ? (s == 1 && sampled ? sampled : &light[s - 1]) : nullptr;
    const PathVertex* pt = t > 0 ? (t == 1 && sampled ? sampled : &camera[t - 1]) : nullptr;
    const PathVertex* qsMinus = s > 1 ? &light[s - 2] : nullptr;
    const PathVertex* ptMinus = t > 1 ? &camera[t - 2] : nullptr;
    EndpointDensities rev;
    if (known) {
        rev = *known;
    } else if (t == 0) {
        // The light subpath reached the lens (qs): the camera samples that point with density
        // 1 / lens area, and the direction to qsMinus as generateRay would.
        rev.qs = paths_.scene().camera().lensPdfArea();
        rev.qsMinus = paths_.pdf(*qs, nullptr, *qsMinus, true);
    } else if (s == 0) {
        // The camera path ends on an emitter (t >= 2 here): a light subpath would start there.
        paths_.emissionDensities(*pt, *ptMinus, &rev.pt, &rev.ptMinus);
    } else {
        rev.pt = paths_.pdf(*qs, qsMinus, *pt, false);
        if (ptMinus) rev.ptMinus = paths_.pdf(*pt, qs, *ptMinus, true);
        rev.qs = paths_.pdf(*pt, ptMinus, *qs, false);
        if (qsMinus) rev.qsMinus = paths_.pdf(*qs, pt, *qsMinus, true);
    }

    // The s = 1 strategy's light choice (Subpaths::lightChoiceRatio) for the path's light
    // vertex y0 and its neighbour y1, where some term needs it.
    float choice = 1;
    if (s == 1) {
        choice = known && known->lightChoice >= 0 ? known->lightChoice : paths_.lightChoiceRatio(*qs, *pt);
    } else if (s == 0 && !camera[t - 2].delta) {
        choice = paths_.lightChoiceRatio(*pt, *ptMinus);
    } else if (s >= 2 && !light[1].delta) {
        choice = prefixes ? prefixes->lightChoice : paths_.lightChoiceRatio(light[0], light[1]);
    }

    if (general_) return weightFromEveryRatio(light, camera, qs, pt, s, t, rev, choice);
    double sum = withHeuristic(heuristic_, [&](auto h) {
        constexpr MisHeuristic H = decltype(h)::value;
        // Beyond the two vertices at each side of the join, each side contributes its
        // running sum: from the prefixes, or walked here.
        double cameraTail = 0, lightTail = 0;
        // The camera-side sums end with the t = 0 strategy's term (lensRatio, 0 without it).
        if (t >= 3 && lensHits_) cameraTail = lensTerm<H>(lensRatio(camera[0].pdfRev, camera[0], camera[1]));
        if (t >= 4 && prefixes) cameraTail = prefixes->camera[t - 3];
        if (t >= 4 && !prefixes)
            for (int m = 1; m <= t - 3; ++m) cameraTail = cameraPrefixStep<H>(camera, m, cameraTail);
        if (s >= 3 && prefixes) lightTail = prefixes->light[s - 3];
        if (s >= 3 && !prefixes)
            for (int m = 0; m <= s - 3; ++m) lightTail = lightPrefixStep<H>(light, m, lightTail, choice);
        // The join's own vertices take this connection's densities, and were reached by a
        // deterministic connection, not a specular bounce. Where a term counts the s = 1
        // strategy (s' = 1 from s = 0, 2 or 3), it carries that strategy's light choice.
        double total = 0;
        if (t >= 2) {
            double inner = 0;
            if (t >= 3) {
                bool valid = !camera[t - 2].delta && !camera[t - 3].delta;
                inner = misTerm<H>(rev.ptMinus, camera[t - 2].pdfFwd) * ((valid ? 1 : 0) + cameraTail);
            } else if (lensHits_) {
                inner = lensTerm<H>(lensRatio(rev.ptMinus, camera[0], *pt));  // (s + 2, 0)
            }
            const double sOne = s == 0 ? choiceTerm<H>(choice) : 1.0;
            const double side = misTerm<H>(rev.pt, pt->pdfFwd) * ((camera[t - 2].delta ? 0 : sOne) + inner);
            total += side;
        } else if (t == 1 && lensHits_) {
            total += lensTerm<H>(lensRatio(rev.pt, *pt, *qs));  // (s + 1, 0)
        }
        if (s >= 1) {
            double inner = 0;
            if (s >= 2) {
                bool valid = !light[s - 2].delta && !(s >= 3 ? light[s - 3].delta : light[0].isDeltaLight());
                const double sOne = s == 3 ? choiceTerm<H>(choice) : 1.0;
                inner = misTerm<H>(rev.qsMinus, light[s - 2].pdfFwd) * ((valid ? sOne : 0) + lightTail);
            }
            bool valid = s >= 2 ? !light[s - 2].delta : !qs->isDeltaLight();
            const double sOne = s == 2 ? choiceTerm<H>(choice) : 1.0;
            total += misTerm<H>(rev.qs, qs->pdfFwd) * ((valid ? sOne : 0) + inner);
        }
        // From s = 1 itself, every other strategy's ratio divides by its light choice.
        if (s == 1) total = choice > 0 ? total * choiceTerm<H>(1 / choice) : 0;
        return total;
    });
    if (!std::isfinite(sum)) return 0;
    return 1.0f / float(1 + sum);
}

// The same walk as misWeight's sums, but each other strategy's density ratio to this one
// is kept (balance terms: the plain ratios), for heuristics whose weight is not a sum of
// per-strategy terms that factor along the path: cutoff and maximum compare every density
// with the largest (thesis §9.2.4), and power with any beta is applied to the ratios here.
// Walks both subpaths: O(path length) per weight.
float BDPTIntegrator::weightFromEveryRatio(const PathVertex* light, const PathVertex* camera, const PathVertex* qs,
                                           const PathVertex* pt, int s, int t, const EndpointDensities& rev,
                                           float choice) const {
    constexpr auto term = misTerm<MisHeuristic::Balance>;
    constexpr int kStack = 64;
    double stack[kStack];
    std::vector<double> heap;
    double* r = stack;
    if (s + t > kStack) {
        heap.resize(size_t(s + t));
        r = heap.data();
    }
    int n = 0;
    const auto keep = [&](double R) { r[n++] = R; };
    // Towards the camera: strategies (s + 1, t - 1), (s + 2, t - 2), ..., t' = 1.
    if (t >= 2) {
        double R = term(rev.pt, pt->pdfFwd);
        if (!camera[t - 2].delta) keep(R * (s == 0 ? choice : 1.0));  // s' = 1 carries its light choice
        if (t >= 3) {
            R *= term(rev.ptMinus, camera[t - 2].pdfFwd);
            if (!camera[t - 2].delta && !camera[t - 3].delta) keep(R);
            for (int m = t - 3; m >= 1; --m) {
                R *= term(camera[m].pdfRev, camera[m].pdfFwd);
                if (!camera[m].delta && !camera[m - 1].delta) keep(R);
            }
        }
        // The t = 0 strategy: the light subpath reaches the lens camera[0] itself.
        const float lens = lensRatio(t >= 3 ? camera[0].pdfRev : rev.ptMinus, camera[0], camera[1]);
        if (lens > 0) keep(R * lens);
    } else if (t == 1) {
        const float lens = lensRatio(rev.pt, *pt, *qs);
        if (lens > 0) keep(lens);
    }
    // Towards the light: strategies (s - 1, t + 1), ..., s' = 0.
    if (s >= 1) {
        double R = term(rev.qs, qs->pdfFwd);
        if (s >= 2 ? !light[s - 2].delta : !qs->isDeltaLight()) keep(R * (s == 2 ? choice : 1.0));
        if (s >= 2) {
            R *= term(rev.qsMinus, light[s - 2].pdfFwd);
            if (!light[s - 2].delta && !(s >= 3 ? light[s - 3].delta : light[0].isDeltaLight()))
                keep(R * (s == 3 ? choice : 1.0));
            for (int m = s - 3; m >= 0; --m) {
                R *= term(light[m].pdfRev, light[m].pdfFwd);
                if (!light[m].delta && !(m > 0 ? light[m - 1].delta : light[0].isDeltaLight()))
                    keep(R * (m == 1 ? choice : 1.0));
            }
        }
    }
    // From s = 1 itself, every other strategy's ratio divides by its light choice.
    if (s == 1) {
        if (!(choice > 0)) return 1;
        for (int i = 0; i < n; ++i) r[i] /= choice;
    }
    return float(mis_.weightFromRatios(r, n));
}

void BDPTIntegrator::setLightPathShare(float share) {
    // 0: every sample the path tracer's, for scenes without delta lights, where light subpaths
    // reach no path that it misses (light_path_choice.h).
    if (!(share >= 0 && share <= 1)) throw std::invalid_argument("the light path share must be in [0, 1]");
    lightPathShare_ = share;
    pathTracer_.reset();
    if (share < 1) pathTracer_ = std::make_unique<PathTracer>(paths_.scene(), paths_.maxDepth(), mis_);
}

// A path the path tracer samples too (its strategies s' = 0 and 1 of BDPT's: the camera walk
// hitting a light that is not delta, or next-event estimation from the path's vertex next to
// the light when that one is not specular) is estimated by the samples without a light
// subpath as well: at weight 1 in samples with one, the two kinds of sample average to it. A
// path only light subpaths reach (a delta light seen through a specular vertex) comes from the
// share that has one alone, and counts 1 / share.
float BDPTIntegrator::lightSubpathScale(const PathVertex* light, int s, int t) const {
    // t >= 1: s <= 1 are the path tracer's own strategies, and at s = 2 the vertex next to
    // the light is the connection's, never specular. t = 0: the light subpath ends on the lens.
    if (lightPathShare_ >= 1 || (t >= 1 && s <= 2)) return 1;
    const bool pathTracerSamples = !light[0].isDeltaLight() || (s >= 2 && !light[1].delta);
    return pathTracerSamples ? 1 : 1 / lightPathShare_;
}

void BDPTIntegrator::recordStrategies(int maxDepth) {
    const Scene& scene = paths_.scene();
    const Camera::Params& cp = scene.camera().params();
    strategies_ = std::make_unique<StrategyImages>(scene.pixelBounds(), cp.xRes, cp.yRes, scene.filter(),
                                                   std::min(maxDepth, paths_.maxDepth()),
                                                   scene.settings().imagingRatio, lensHits_);
}

Spectrum BDPTIntegrator::Li(const Ray& ray, SampleContext& ctx) const {
    return withConcreteSampler(ctx.sampler, [&](auto& sampler) { return estimate(ray, sampler, ctx); });
}

// Produces every strategy's contribution of one camera and one light subpath: deposit(s, t, c)
// receives each that is not black (t = 1: landing at c.pRaster; else on the camera ray's
// film position). The subpaths and the connections draw from their own dimension streams.
// onlyDepth >= 0: the subpaths stop at the lengths that depth needs, and only its
// strategies are connected.
template <typename S, typename Deposit>
void BDPTIntegrator::produce(const Ray& ray, S& sampler, ScratchBuffer& scratch, PathStats& stats,
                             const SampleContext* splatTo, Deposit&& deposit, int onlyDepth,
                             SampledWavelengths* lambda) const {
    const int cameraVertices = onlyDepth >= 0 ? onlyDepth + 2 : paths_.maxCameraVertices();
    // With lens hits a light subpath takes one vertex more (Subpaths::maxLightVertices).
    const int lightVertices = onlyDepth >= 0 ? onlyDepth + 1 + (lensHits_ ? 1 : 0) : paths_.maxLightVertices();
    PathVertex* camera = allocPath(scratch, cameraVertices);
    PathVertex* light = allocPath(scratch, lightVertices);
    // The light subpath's origin first: its sampling then overlaps the camera walk.
    if (splatTo) lambda = splatTo->lambda;
    sampler.startStream(kLightStream);
    // With a light path share below 1, estimate() decided on the light stream's first
    // dimension that this sample traces a light subpath (setLightPathShare).
    if (lightPathShare_ < 1) sampler.get1D();
    const Subpaths::LightOrigin origin = paths_.lightOrigin(sampler, ray.time, stats, light, lambda);
    sampler.startStream(kCameraStream);
    std::optional<MediaSample> media;
    if (paths_.scene().hasMedia()) media = paths_.mediaSample(sampler, lambda);
    const MediaSample* ms = media ? &*media : nullptr;
    int nCamera = paths_.cameraSubpath(ray, sampler, scratch, stats, camera, cameraVertices, lambda, ms);
    sampler.startStream(kLightStream);
    LensHits lensHits;
    if (lensHits_) {
        lensHits.capacity = lightVertices;
        lensHits.hits = static_cast<LensHit*>(scratch.allocBytes(sizeof(LensHit) * size_t(lightVertices), alignof(LensHit)));
    }
    const int nLight = paths_.continueLightSubpath(origin, sampler, scratch, stats, light, lightVertices, lambda, ms,
                                                   lensHits_ ? &lensHits : nullptr);
    sampler.startStream(kConnectionStream);
    const MisPrefixes prefixes = misPrefixes(light, nLight, camera, nCamera, scratch);

    const int maxDepth = paths_.maxDepth();
    // s = 1 samples its own light vertex (joinLight), so it runs even when the light subpath
    // is empty: its origin can fail where light sampling succeeds (a cut-out point of an
    // emitter with alpha), and skipping s = 1 then would bias it by the chance of that failure.
    const int sMax = std::max(nLight, 1);
    for (int t = 1; t <= nCamera; ++t)
        for (int s = 0; s <= sMax; ++s) {
            int depth = s + t - 2;
            // (1,1) would see a light through the lens by sampling both ends; the camera
            // ray finding the light (0,2) covers those paths with weight 1.
            if ((s == 1 && t == 1) || (t == 1 && camera[0].delta) || depth < 0 || depth > maxDepth || (onlyDepth >= 0 && depth != onlyDepth)) continue;
            // Most camera vertices emit nothing: skip the call for the s = 0 strategy.
            if (s == 0 && !camera[t - 1].isLight()) continue;
            sampler.seekDimension(connectionDimension(s, t));
            Connection c = connect(light, camera, s, t, sampler, stats, true, &prefixes, splatTo, lambda, ms);
            if (c.L.isBlack()) continue;
            c.L *= lightSubpathScale(light, s, t);
            c.dispersive = lambda && usesDispersiveVertex(light, camera, s, t);
            deposit(s, t, c);
        }
    // Emission inside media that the camera walk met along its flights: strategy (0, k + 2)
    // for the flight leaving camera vertex k, with weight 1 under every heuristic, since no
    // other strategy has a density for it (subpaths_media.cpp collects it at pbrt-v4's
    // depths, k < maxdepth).
    if (ms)
        for (int k = 0; k < nCamera; ++k) {
            if (camera[k].mediumLe.isBlack() || (onlyDepth >= 0 && k != onlyDepth)) continue;
            Connection c;
            c.L = camera[k].mediumLe;
            c.weight = 1;
            c.dispersive = lambda && usesDispersiveVertex(light, camera, 0, k + 1);
            deposit(0, k + 2, c);
        }
    // t = 0: the light subpath's rays that crossed the lens (lens_hits.h).
    for (int i = 0; i < lensHits.n; ++i) {
        const LensHit& hit = lensHits.hits[i];
        const int s = hit.index + 1, depth = s - 2;
        if (depth > maxDepth || (onlyDepth >= 0 && depth != onlyDepth)) continue;
        Connection c = connectLens(light, hit, scratch, &prefixes);
        if (c.L.isBlack()) continue;
        c.L *= lightSubpathScale(light, s, 0);
        c.dispersive = lambda && usesDispersiveVertex(light, nullptr, hit.index, 0);
        deposit(s, 0, c);
    }
}

template <typename S>
Spectrum BDPTIntegrator::estimate(const Ray& ray, S& sampler, SampleContext& ctx) const {
    if (pathTracer_) {
        // A light subpath for a share of the samples; the others are the path tracer's, whose
        // strategies are BDPT's s = 0 and 1 without the light subpath's cost (lightSubpathScale).
        sampler.startStream(kLightStream);
        if (!(sampler.get1D() < lightPathShare_)) {
            sampler.startStream(kCameraStream);
            SampleContext alone = ctx;
            alone.tally = nullptr;  // its own techniques' indices are not BDPT's
            const Spectrum L = pathTracer_->Li(ray, alone);
            if (ctx.tally) ctx.tally->addCamera(pathTechniqueIndex(), ctx.toFilm(L));
            return L;
        }
    }
    ScratchBuffer& scratch = ctx.scratch;
    Spectrum L;
    Spectrum* perStrategy = nullptr;
    if (strategies_) {
        size_t n = size_t(strategies_->slotCount()) * 2;
        perStrategy = static_cast<Spectrum*>(scratch.allocBytes(sizeof(Spectrum) * n, alignof(Spectrum)));
        for (size_t i = 0; i < n; ++i) new (&perStrategy[i]) Spectrum();
    }
    produce(ray, sampler, scratch, ctx.stats, &ctx, [&](int s, int t, const Connection& c) {
        Spectrum contribution = c.L * c.weight;
        if (strategies_ && t == 0)  // the t = 0 strategy lands where the lens maps its ray
            strategies_->splatLens(s, c.pRaster, ctx.toFilm(contribution), ctx.toFilm(c.L), ctx.sampleIndex);
        if (strategies_ && t >= 1) {  // the strategy images hold t >= 1
            if (t == 1) {
                strategies_->splat(s, c.pRaster, ctx.toFilm(contribution), ctx.toFilm(c.L), ctx.sampleIndex);
            } else if (int k = strategies_->slot(s, t); k >= 0) {
                // Added: strategy (0, t) may come twice, from an emitter the walk hit and from a
                // medium's emission along the flight before it.
                perStrategy[2 * k] += ctx.toFilm(contribution);
                perStrategy[2 * k + 1] += ctx.toFilm(c.L);
            }
        }
        if (c.weight == 0) return;
        if (ctx.tally) {
            if (t <= 1) ctx.tally->addSplat(techniqueIndex(s, t), ctx.toFilm(contribution), c.pRaster);
            else ctx.tally->addCamera(techniqueIndex(s, t), ctx.toFilm(contribution));
        }
        if (t <= 1) ctx.film.addSplat(c.pRaster, ctx.toFilm(contribution), ctx.sampleIndex);
        else L += contribution;
    });
    if (strategies_) strategies_->addCameraSample(ctx.px, ctx.py, ctx.filterWeight, perStrategy);
    return L;
}

void BDPTIntegrator::contributions(const Ray& ray, Vec2 pFilm, PrimarySampleSampler& sampler, ScratchBuffer& scratch,
                                   PathStats& stats, std::vector<PathContribution>& out, int onlyDepth,
                                   SampledWavelengths* lambda) const {
    out.clear();
    if (onlyDepth > paths_.maxDepth()) return;
    produce(
        ray, sampler, scratch, stats, nullptr,
        [&](int s, int t, const Connection& c) {
            if (c.weight == 0) return;
            out.push_back({t <= 1 ? c.pRaster : pFilm, c.L * c.weight, s, t, c.dispersive});
        },
        onlyDepth, lambda);
}

bool BDPTIntegrator::strategyContribution(const Ray& ray, Vec2 pFilm, int s, int t, PrimarySampleSampler& sampler,
                                          ScratchBuffer& scratch, PathStats& stats, PathContribution& out,
                                          SampledWavelengths* lambda) const {
    if (t < 1 || s < 0 || t > paths_.maxCameraVertices() || s > paths_.maxLightVertices() || (s == 1 && t == 1))
        return false;
    PathVertex* camera = allocPath(scratch, t);
    PathVertex* light = allocPath(scratch, std::max(s, 1));
    std::optional<MediaSample> media;
    if (paths_.scene().hasMedia()) {
        sampler.startStream(kCameraStream);
        media = paths_.mediaSample(sampler, lambda);
    }
    const MediaSample* ms = media ? &*media : nullptr;
    // s = 1 samples its light vertex in the connection (joinLight): no light subpath.
    if (s > 1) {
        sampler.startStream(kLightStream);
        const Subpaths::LightOrigin origin = paths_.lightOrigin(sampler, ray.time, stats, light, lambda);
        if (paths_.continueLightSubpath(origin, sampler, scratch, stats, light, s, lambda, ms) != s) return false;
    }
    sampler.startStream(kCameraStream);
    const int nCamera = paths_.cameraSubpath(ray, sampler, scratch, stats, camera, t, lambda, ms);
    // s = 0 in an emissive medium: the emission along the flight from camera vertex t - 2,
    // whatever that flight then did (produce's strategy (0, t), weight 1).
    Spectrum L;
    bool dispersive = false;
    if (s == 0 && ms && t >= 2 && nCamera >= t - 1 && !camera[t - 2].mediumLe.isBlack()) {
        L = camera[t - 2].mediumLe;
        dispersive = lambda && usesDispersiveVertex(light, camera, 0, t - 1);
    }
    if (nCamera == t) {
        sampler.startStream(kConnectionStream);
        sampler.seekDimension(connectionDimension(s, t));
        Connection c = connect(light, camera, s, t, sampler, stats, true, nullptr, nullptr, lambda, ms);
        if (!c.L.isBlack() && c.weight != 0) {
            L += c.L * c.weight;
            dispersive = dispersive || (lambda && usesDispersiveVertex(light, camera, s, t));
            if (t == 1) pFilm = c.pRaster;
        }
    }
    if (L.isBlack()) return false;
    out = {pFilm, L, s, t, dispersive};
    return true;
}

template BDPTIntegrator::Connection BDPTIntegrator::connect<Sampler>(PathVertex*, PathVertex*, int, int, Sampler&,
                                                                     PathStats&, bool, const MisPrefixes*,
                                                                     const SampleContext*, const SampledWavelengths*,
                                                                     const MediaSample*) const;

}  // namespace ps
