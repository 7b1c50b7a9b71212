#include "transport/light_tracer.h"

#include <new>

namespace ps {

void LightTracer::splatEmitter(const PathVertex& v, SampleContext& ctx) const {
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
    if (!bdpt_.subpaths().visible(v, lens, ctx.stats)) return;
    ctx.film.addSplat(cs->pRaster, ctx.toFilm(L), ctx.sampleIndex);
}

// The camera ray is not traced; its time (the camera sample's, uniform over the shutter) is
// the one time of this light path.
Spectrum LightTracer::Li(const Ray& cameraRay, SampleContext& ctx) const {
    const Subpaths& paths = bdpt_.subpaths();
    int n = paths.maxLightVertices();
    auto* light = static_cast<PathVertex*>(ctx.scratch.allocBytes(sizeof(PathVertex) * size_t(n), alignof(PathVertex)));
    for (int i = 0; i < n; ++i) new (&light[i]) PathVertex();
    int nLight = paths.lightSubpath(ctx.sampler, cameraRay.time, ctx.scratch, ctx.stats, light, ctx.lambda);
    if (nLight > 0) splatEmitter(light[0], ctx);
    PathVertex camera[1];
    for (int s = 2; s <= nLight; ++s) {
        auto c = bdpt_.connect(light, camera, s, 1, ctx.sampler, ctx.stats, false, nullptr, &ctx);
        if (!c.L.isBlack()) ctx.film.addSplat(c.pRaster, ctx.toFilm(c.L), ctx.sampleIndex);
    }
    return {};
}

}  // namespace ps
