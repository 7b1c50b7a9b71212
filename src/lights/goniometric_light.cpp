#include "lights/goniometric_light.h"

#include <algorithm>

#include "math/equal_area.h"

namespace ps {

Transform GoniometricLight::swapYZ() {
    Matrix4 m;
    m.m[1][1] = m.m[2][2] = 0;
    m.m[1][2] = m.m[2][1] = 1;
    return Transform(m, m);  // its own inverse
}

GoniometricLight::GoniometricLight(const Transform& worldFromLight, LightSpectrum I, std::vector<float> values, int res)
    : Light(LightType::DeltaPosition), frame_(worldFromLight * swapYZ()), pos_(frame_.position()), I_(I),
      values_(std::move(values)), res_(res) {
    for (float& v : values_) v = std::max(v, 0.0f);
    // Equal-area texels: a density proportional to the texel over the square is one over
    // the sphere too (texel solid angle 4 pi / N everywhere).
    distribution_ = Distribution2D(values_, res_, res_);
}

Spectrum GoniometricLight::intensityLight(Vec3 wLight, const SampledWavelengths* lambda) const {
    Vec2 uv = equalAreaSphereToSquare(wLight);
    int x = std::clamp(int(uv.x * res_), 0, res_ - 1), y = std::clamp(int(uv.y * res_), 0, res_ - 1);
    return I_(lambda) * values_[size_t(y) * res_ + x];
}

std::optional<LightLiSample> GoniometricLight::sampleLi(const LightSampleContext& ctx, Vec2) const {
    return pointLightLi(pos_, ctx, [&](Vec3 w) { return intensity(w, ctx.lambda); });
}

std::optional<LightLeSample> GoniometricLight::sampleLe(Vec2, Vec2 uDir, const SampledWavelengths* lambda) const {
    float pdfUV;
    Vec2 uv = distribution_.sampleContinuous(uDir, &pdfUV);
    if (!(pdfUV > 0)) return std::nullopt;
    Vec3 wLight = equalAreaSquareToSphere(uv);
    float pdfDir = frame_.toWorldDensity(pdfUV / (4 * kPi), wLight);
    Spectrum I = intensityLight(wLight, lambda);
    if (!(pdfDir > 0) || I.isBlack()) return std::nullopt;
    return LightLeSample{I, Ray{pos_, frame_.toWorld(wLight)}, {}, 1.0f, pdfDir, {}};
}

// The position is a delta (density 0 for every other strategy).
void GoniometricLight::pdfLe(Vec3, Vec3, Vec3 w, float* pdfPos, float* pdfDir) const {
    *pdfPos = 0;
    Vec3 wLight = frame_.toLight(w);
    *pdfDir = frame_.toWorldDensity(distribution_.pdf(equalAreaSphereToSquare(wLight)) / (4 * kPi), wLight);
}

float GoniometricLight::meanValue() const {
    double sum = 0;
    for (float v : values_) sum += v;
    return float(sum / values_.size());
}

Spectrum GoniometricLight::phi() const { return I_.rgb() * (4 * kPi * meanValue()); }

// Bounded as a point light of its mean intensity, weighed by its spectrum's maximum.
std::optional<LightBounds> GoniometricLight::bounds() const {
    return LightBounds(Bounds3(pos_), {0, 0, 1}, 4 * kPi * meanValue() * I_.maxValue(), -1, 0, false);
}

}  // namespace ps
