// Light from infinitely far away in every direction: a constant sky, or an environment
// image (pbrt-v4's square equal-area maps; 2:1 latitude-longitude maps as well)
// importance-sampled by its luminance.
#pragma once
#include "image/image.h"
#include "lights/light.h"
#include "math/transform.h"
#include "mc/distribution.h"

namespace ps {

class UniformInfiniteLight final : public Light {
public:
    explicit UniformInfiniteLight(LightSpectrum L) : Light(LightType::Infinite), L_(std::move(L)) {}
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const override;
    float pdfLi(const LightSampleContext& ctx, Vec3 wi, const SurfaceInteraction* hit) const override;
    std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const override;
    void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const override;
    Spectrum Le(const Ray&, const SampledWavelengths* lambda) const override { return L_(lambda); }
    Spectrum phi() const override { return L_.rgb() * (4 * kPi * kPi * sceneRadius_ * sceneRadius_); }
    void preprocess(Vec3 c, float r) override { sceneCenter_ = c; sceneRadius_ = r; }

private:
    LightSpectrum L_;
    Vec3 sceneCenter_;
    float sceneRadius_ = 1;
};

class ImageInfiniteLight final : public Light {
public:
    enum class Layout { EqualArea, LatLong };
    ImageInfiniteLight(Image image, float scale, const Transform& worldFromLight, Layout layout);
    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const override;
    float pdfLi(const LightSampleContext& ctx, Vec3 wi, const SurfaceInteraction* hit) const override;
    std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const override;
    void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const override;
    Spectrum Le(const Ray& r, const SampledWavelengths* lambda) const override { return lookup(normalize(r.d), lambda); }
    Spectrum phi() const override;
    void preprocess(Vec3 c, float r) override { sceneCenter_ = c; sceneRadius_ = r; }

private:
    // The image's RGB times scale; in spectral mode lifted as an illuminant at lambda.
    Spectrum lookup(Vec3 wWorld, const SampledWavelengths* lambda = nullptr) const;
    Vec2 directionToUV(Vec3 wLight) const;
    Vec3 uvToDirection(Vec2 uv) const;
    // Density of a direction with respect to the unit square's density pdfUV.
    float uvPdfToSolidAngle(float pdfUV, Vec2 uv) const;

    Image image_;
    float scale_;
    Transform worldFromLight_;
    Layout layout_;
    Distribution2D distribution_;
    Vec3 sceneCenter_;
    float sceneRadius_ = 1;
};

}  // namespace ps
