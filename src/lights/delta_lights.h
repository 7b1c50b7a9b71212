// Lights described by a delta distribution: point and spot (one position), distant (one
// direction). Only light sampling can find them, so no MIS weight applies.
#pragma once
#include "lights/light.h"
#include "math/frame.h"

namespace ps {

class PointLight final : public Light {
public:
    PointLight(Vec3 pos, LightSpectrum I) : Light(LightType::DeltaPosition), pos_(pos), I_(std::move(I)) {}
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const override;
    std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const override;
    void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const override;
    Spectrum L(Vec3, Vec3, Vec2, Vec3, const SampledWavelengths* lambda) const override { return I_(lambda); }
    Spectrum phi() const override { return I_.rgb() * (4 * kPi); }
    std::optional<LightBounds> bounds() const override;

private:
    Vec3 pos_;
    LightSpectrum I_;
};

class SpotLight final : public Light {
public:
    // cosFalloffEnd = cos(coneangle), cosFalloffStart = cos(coneangle - conedelta).
    SpotLight(Vec3 pos, Vec3 axis, LightSpectrum I, float cosFalloffStart, float cosFalloffEnd)
        : Light(LightType::DeltaPosition), pos_(pos), frame_(Frame::fromNormal(normalize(axis))), I_(std::move(I)),
          cosStart_(cosFalloffStart), cosEnd_(cosFalloffEnd) {}
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const override;
    std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const override;
    void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const override;
    Spectrum L(Vec3, Vec3, Vec2, Vec3 w, const SampledWavelengths* lambda) const override { return intensity(w, lambda); }
    Spectrum phi() const override;
    std::optional<LightBounds> bounds() const override;
    // Intensity towards world direction w leaving the light.
    Spectrum intensity(Vec3 w, const SampledWavelengths* lambda = nullptr) const;

private:
    Vec3 pos_;
    Frame frame_;
    LightSpectrum I_;
    float cosStart_, cosEnd_;
};

class DistantLight final : public Light {
public:
    // wLight: unit direction towards the light (light travels along -wLight).
    DistantLight(Vec3 wLight, LightSpectrum L) : Light(LightType::DeltaDirection), w_(wLight), L_(std::move(L)) {}
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const override;
    std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const override;
    void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const override;
    Spectrum phi() const override { return L_.rgb() * (kPi * sceneRadius_ * sceneRadius_); }
    void preprocess(Vec3 c, float r) override { sceneCenter_ = c; sceneRadius_ = r; }

private:
    Vec3 w_;
    LightSpectrum L_;
    Vec3 sceneCenter_;
    float sceneRadius_ = 1;
};

}  // namespace ps
