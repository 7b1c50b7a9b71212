#include "lights/area_light.h"

#include "math/frame.h"
#include "math/warp.h"

namespace ps {

std::optional<LightLiSample> DiffuseAreaLight::sampleLi(const LightSampleContext& ctx, Vec2 u) const {
    auto s = shape_->sampleToward(prim_, ctx.p, u);
    if (!s) return std::nullopt;
    Spectrum Le = L(s->p, s->n, s->uv, -s->wi, ctx.lambda);
    if (Le.isBlack()) return std::nullopt;
    return LightLiSample{Le, s->wi, s->pdf, s->p, s->n, s->pdfArea, emittedDirectionPdf(dot(s->n, -s->wi))};
}

float DiffuseAreaLight::pdfLi(const LightSampleContext& ctx, Vec3, const SurfaceInteraction* hit) const {
    if (!hit) return 0;
    return shape_->pdfToward(prim_, ctx.p, hit->p, hit->ng);
}

// Uniform by area, cosine-weighted about the emitting side's normal (either side with
// probability 1/2 when two-sided).
std::optional<LightLeSample> DiffuseAreaLight::sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const {
    ShapeSample s = shape_->sampleArea(prim_, uPos);
    if (!(s.pdf > 0)) return std::nullopt;
    if (alpha_ && !alpha_->keepsPoint(s.p, s.n, s.uv)) return std::nullopt;
    Vec3 n = s.n;
    float sidePdf = 1;
    if (twoSided_) {
        sidePdf = 0.5f;
        if (uDir.x < 0.5f) {
            uDir.x *= 2;
        } else {
            uDir.x = std::min((uDir.x - 0.5f) * 2, 0x1.fffffep-1f);
            n = -n;
        }
    }
    Vec3 wLocal = sampleCosineHemisphere(uDir);
    if (!(wLocal.z > 0)) return std::nullopt;
    Vec3 w = Frame::fromNormal(n).toWorld(wLocal);
    LightLeSample ls;
    ls.L = L(s.p, s.n, s.uv, w, lambda);
    ls.ray = spawnRay(s.p, s.n, w, 0);  // the light subpath stamps its path's time on it
    ls.ray.o = s.p;  // the vertex is on the light; callers offset when they trace
    ls.n = s.n;
    ls.uv = s.uv;
    ls.pdfPos = s.pdf;
    ls.pdfDir = sidePdf * cosineHemispherePdf(wLocal.z);
    return ls;
}

// Weighed by the spectrum's maximum (an image: its channels' mean) times pi times the area, as
// pbrt-v4: a two-sided emitter is not counted twice, since a point sees one of its sides.
std::optional<LightBounds> DiffuseAreaLight::bounds() const {
    DirectionCone normals = shape_->normalBounds(prim_);
    const float radiance = image_ ? image_->mean().average() * Lemit_.rgb().g : Lemit_.maxValue();
    return LightBounds(shape_->primitiveBounds(prim_), normals.w, radiance * kPi * shape_->area(prim_),
                       normals.cosTheta, 0, twoSided_);
}

void DiffuseAreaLight::pdfLe(Vec3, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const {
    *pdfPos = shape_->pdfArea(prim_);
    *pdfDir = emittedDirectionPdf(dot(n, w));
}

}  // namespace ps
