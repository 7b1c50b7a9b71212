#include "lights/delta_lights.h"

#include "lights/infinity_disk.h"
#include "math/warp.h"

namespace ps {

std::optional<LightLiSample> PointLight::sampleLi(const LightSampleContext& ctx, Vec2) const {
    return pointLightLi(pos_, ctx, [&](Vec3) { return I_(ctx.lambda); });
}

std::optional<LightLeSample> PointLight::sampleLe(Vec2, Vec2 uDir, const SampledWavelengths* lambda) const {
    return LightLeSample{I_(lambda), Ray{pos_, sampleUniformSphere(uDir)}, {}, 1.0f, uniformSpherePdf(), {}};
}

// The position is a delta (density 0 for every other strategy); directions are uniform.
void PointLight::pdfLe(Vec3, Vec3, Vec3, float* pdfPos, float* pdfDir) const {
    *pdfPos = 0;
    *pdfDir = uniformSpherePdf();
}

// Point-like lights weigh in as 4 pi times their intensity (pbrt-v4's choice), not their
// power: what a point receives from them is intensity / d^2 wherever they shine at all, so a
// spot light weighs as much as a point light of its intensity inside its cone.
std::optional<LightBounds> PointLight::bounds() const {
    return LightBounds(Bounds3(pos_), {0, 0, 1}, 4 * kPi * I_.maxValue(), -1, 0, false);
}

static float smoothStep(float x, float a, float b) {
    if (a == b) return x < a ? 0.0f : 1.0f;
    float t = clampf((x - a) / (b - a), 0, 1);
    return t * t * (3 - 2 * t);
}

Spectrum SpotLight::intensity(Vec3 w, const SampledWavelengths* lambda) const {
    float cosT = dot(w, frame_.n);
    return I_(lambda) * smoothStep(cosT, cosEnd_, cosStart_);
}

std::optional<LightLiSample> SpotLight::sampleLi(const LightSampleContext& ctx, Vec2) const {
    return pointLightLi(pos_, ctx, [&](Vec3 w) { return intensity(w, ctx.lambda); });
}

// Directions uniform in the whole cone; the falloff weights the intensity.
std::optional<LightLeSample> SpotLight::sampleLe(Vec2, Vec2 uDir, const SampledWavelengths* lambda) const {
    Vec3 w = frame_.toWorld(sampleUniformCone(uDir, cosEnd_));
    Spectrum I = intensity(w, lambda);
    if (I.isBlack()) return std::nullopt;
    return LightLeSample{I, Ray{pos_, w}, {}, 1.0f, uniformConePdf(cosEnd_), {}};
}

void SpotLight::pdfLe(Vec3, Vec3, Vec3 w, float* pdfPos, float* pdfDir) const {
    *pdfPos = 0;
    *pdfDir = dot(w, frame_.n) >= cosEnd_ ? uniformConePdf(cosEnd_) : 0.0f;
}

// Integral of the smoothstep falloff over the sphere (PBRT-CONVENTIONS §3).
Spectrum SpotLight::phi() const {
    return I_.rgb() * (2 * kPi * ((1 - cosStart_) + (cosStart_ - cosEnd_) / 2));
}

// Directions within the falloff's start have full intensity (theta_o); it reaches zero at the
// cone's edge, theta_e further. A margin of 1e-3 radians keeps rounding from zeroing the
// bound for directions the light still reaches (for a cone without falloff, theta_e is 0).
std::optional<LightBounds> SpotLight::bounds() const {
    float thetaE = safeAcos(cosEnd_) - safeAcos(cosStart_) + 1e-3f;
    return LightBounds(Bounds3(pos_), frame_.n, 4 * kPi * I_.maxValue(), cosStart_, std::cos(thetaE), false);
}

std::optional<LightLiSample> DistantLight::sampleLi(const LightSampleContext& ctx, Vec2) const {
    Vec3 pOutside = ctx.p + w_ * (2 * sceneRadius_ + length(ctx.p - sceneCenter_));
    return LightLiSample{L_(ctx.lambda), w_, 1.0f, pOutside, {}};
}

std::optional<LightLeSample> DistantLight::sampleLe(Vec2 uPos, Vec2, const SampledWavelengths* lambda) const {
    return LightLeSample{L_(lambda), rayFromInfinityDisk(w_, sceneCenter_, sceneRadius_, uPos), {},
                         infinityDiskPdf(sceneRadius_), 1.0f, {}};
}

void DistantLight::pdfLe(Vec3, Vec3, Vec3, float* pdfPos, float* pdfDir) const {
    *pdfPos = infinityDiskPdf(sceneRadius_);
    *pdfDir = 0;  // a delta direction: never chosen by another strategy
}

}  // namespace ps
