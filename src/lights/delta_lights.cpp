#include "lights/delta_lights.h"

namespace ps {

std::optional<LightLiSample> PointLight::sampleLi(const LightSampleContext& ctx, Vec2) const {
    Vec3 d = pos_ - ctx.p;
    float d2 = lengthSquared(d);
    if (!(d2 > 0)) return std::nullopt;
    return LightLiSample{I_ / d2, d / std::sqrt(d2), 1.0f, pos_, {}};
}

static float smoothStep(float x, float a, float b) {
    if (a == b) return x < a ? 0.0f : 1.0f;
    float t = clampf((x - a) / (b - a), 0, 1);
    return t * t * (3 - 2 * t);
}

Spectrum SpotLight::intensity(Vec3 w) const {
    float cosT = dot(w, frame_.n);
    return I_ * smoothStep(cosT, cosEnd_, cosStart_);
}

std::optional<LightLiSample> SpotLight::sampleLi(const LightSampleContext& ctx, Vec2) const {
    Vec3 d = pos_ - ctx.p;
    float d2 = lengthSquared(d);
    if (!(d2 > 0)) return std::nullopt;
    Vec3 wi = d / std::sqrt(d2);
    Spectrum I = intensity(-wi);
    if (I.isBlack()) return std::nullopt;
    return LightLiSample{I / d2, wi, 1.0f, pos_, {}};
}

// Integral of the smoothstep falloff over the sphere (PBRT-CONVENTIONS §3).
Spectrum SpotLight::phi() const {
    return I_ * (2 * kPi * ((1 - cosStart_) + (cosStart_ - cosEnd_) / 2));
}

std::optional<LightLiSample> DistantLight::sampleLi(const LightSampleContext& ctx, Vec2) const {
    Vec3 pOutside = ctx.p + w_ * (2 * sceneRadius_ + length(ctx.p - sceneCenter_));
    return LightLiSample{L_, w_, 1.0f, pOutside, {}};
}

}  // namespace ps
