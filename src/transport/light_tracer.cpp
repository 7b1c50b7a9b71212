#include "transport/light_tracer.h"

#include <algorithm>
#include <new>
#include <optional>

namespace ps {

namespace {
// The Rng stream of the emitter's own connection to the lens (past every BDPT connection's).
constexpr uint64_t kEmitterStream = uint64_t(1) << 40;
}  // namespace

void LightTracer::splatEmitter(const PathVertex& v, SampleContext& ctx, const MediaSample* media) const {
    // Lights at infinity emit along one direction per disk point: the lens never sees them
    // here. Point and spot lights seen directly are not imaged either, as in path tracing
    // (and pbrt-v4): a camera ray cannot hit them.
    if (v.infinite || !v.light || v.light->isDelta()) return;
    const Scene& scene = bdpt_.subpaths().scene();
    auto cs = scene.camera().sampleWi(v.p, v.time, ctx.sampler.get2D());
    if (!cs || !(v.pdfFwd > 0)) return;
    Spectrum Le = v.light->L(v.p, v.ng, v.uv, cs->wi, ctx.lambda);
    if (Le.isBlack()) return;
    float cosLight = v.onSurface() ? std::fabs(dot(v.ng, cs->wi)) : 1.0f;
    Spectrum L = Le * (cosLight * cs->We / (cs->pdf * v.pdfFwd));
    PathVertex lens;
    lens.p = cs->pLens;
    lens.time = v.time;
    if (!bdpt_.subpaths().connectThrough(v, lens, v.rU, ctx.stats, media, kEmitterStream, L)) return;
    ctx.film.addSplat(cs->pRaster, ctx.toFilm(L), ctx.sampleIndex);
}

// The t = 0 strategy (lens_hits.h) where t = 1 cannot sample the path: the vertex before the
// lens is specular (a delta light's highlight in a mirror, thesis §1.1) or not connectible.
// Elsewhere the lens connection (t = 1) has it: light tracing adds each path once, unweighted.
void LightTracer::splatLensHits(const PathVertex* light, const LensHits& lens, SampleContext& ctx) const {
    for (int i = 0; i < lens.n; ++i) {
        const LensHit& hit = lens.hits[i];
        const PathVertex& before = light[hit.index - 1];
        if (hit.index - 1 > bdpt_.subpaths().maxDepth() || (before.connectible() && !before.delta)) continue;
        const Spectrum L = hit.beta * hit.lens.We;
        if (L.isBlack() || !L.isFinite()) continue;
        ctx.film.addSplat(hit.lens.pRaster, ctx.toFilm(L), ctx.sampleIndex);
    }
}

// The camera ray is not traced; its time (the camera sample's, uniform over the shutter) is
// the one time of this light path.
Spectrum LightTracer::Li(const Ray& cameraRay, SampleContext& ctx) const {
    const Subpaths& paths = bdpt_.subpaths();
    int n = paths.maxLightVertices();
    auto* light = static_cast<PathVertex*>(ctx.scratch.allocBytes(sizeof(PathVertex) * size_t(n), alignof(PathVertex)));
    for (int i = 0; i < n; ++i) new (&light[i]) PathVertex();
    std::optional<MediaSample> media;
    if (paths.scene().hasMedia()) media = paths.mediaSample(ctx.sampler, ctx.lambda);
    const MediaSample* ms = media ? &*media : nullptr;
    LensHits lens;
    if (paths.lensHits()) {
        lens.capacity = n;
        lens.hits = static_cast<LensHit*>(ctx.scratch.allocBytes(sizeof(LensHit) * size_t(n), alignof(LensHit)));
    }
    int nLight = paths.lightSubpath(ctx.sampler, cameraRay.time, ctx.scratch, ctx.stats, light, ctx.lambda, ms,
                                    paths.lensHits() ? &lens : nullptr);
    if (nLight > 0) splatEmitter(light[0], ctx, ms);
    splatLensHits(light, lens, ctx);
    PathVertex camera[1];
    // With lens hits the subpath has one vertex more, for t = 0 alone (Subpaths::maxLightVertices).
    const int sMax = std::min(nLight, paths.maxDepth() + 1);
    for (int s = 2; s <= sMax; ++s) {
        auto c = bdpt_.connect(light, camera, s, 1, ctx.sampler, ctx.stats, false, nullptr, &ctx, nullptr, ms);
        if (!c.L.isBlack()) ctx.film.addSplat(c.pRaster, ctx.toFilm(c.L), ctx.sampleIndex);
    }
    return {};
}

}  // namespace ps
