#include "lights/area_light.h"

namespace ps {

std::optional<LightLiSample> DiffuseAreaLight::sampleLi(const LightSampleContext& ctx, Vec2 u) const {
    auto s = shape_->sampleToward(prim_, ctx.p, u);
    if (!s) return std::nullopt;
    Spectrum Le = L(s->p, s->n, s->uv, -s->wi);
    if (Le.isBlack()) return std::nullopt;
    return LightLiSample{Le, s->wi, s->pdf, s->p, s->n};
}

float DiffuseAreaLight::pdfLi(const LightSampleContext& ctx, Vec3, const SurfaceInteraction* hit) const {
    if (!hit) return 0;
    return shape_->pdfToward(prim_, ctx.p, hit->p, hit->ng);
}

}  // namespace ps
