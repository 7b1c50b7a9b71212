#include "lights/area_light.h"

namespace ps {

std::optional<LightLiSample> DiffuseAreaLight::sampleLi(const LightSampleContext& ctx, Vec2 u) const {
    auto s = shape_->sampleToward(prim_, ctx.p, u);
    if (!s) return std::nullopt;
    Vec3 d = s->p - ctx.p;
    float dist = length(d);
    if (!(dist > 0)) return std::nullopt;
    Vec3 wi = d / dist;
    Spectrum Le = L(s->p, s->n, s->uv, -wi);
    if (Le.isBlack()) return std::nullopt;
    return LightLiSample{Le, wi, s->pdf, s->p, s->n};
}

float DiffuseAreaLight::pdfLi(const LightSampleContext& ctx, Vec3, const SurfaceInteraction* hit) const {
    if (!hit) return 0;
    return shape_->pdfToward(prim_, ctx.p, hit->p, hit->ng);
}

}  // namespace ps
