// pbrt-v4's "diffuse" area light: constant radiance over one primitive of a shape,
// one-sided (the side of the oriented normal) unless twosided. On a shape with alpha, points
// the alpha test cuts out do not emit (pbrt-v4's semantics); the test is the point's own (see
// Shape::keepsHit), so a point emits for light sampling exactly when rays see it. A constant
// alpha 0 is pbrt-v4's invisible light: rays never hit it, it emits unmasked, and, like a
// point light, it is reached by light sampling only (no MIS with strategies that hit it).
// With an emission image (pbrt-v4's "filename") the radiance varies over the primitive's uv.
#pragma once
#include <memory>
#include "geometry/shape.h"
#include "lights/emission_image.h"
#include "lights/light.h"
#include "math/warp.h"

namespace ps {

class DiffuseAreaLight final : public Light {
public:
    // Lemit: the radiance, or with an image the factor (scale) that multiplies its values.
    DiffuseAreaLight(const Shape* shape, int prim, LightSpectrum Lemit, bool twoSided,
                     std::shared_ptr<const EmissionImage> image = nullptr)
        : Light(shape->alpha && shape->alpha->alwaysMasked() ? LightType::DeltaPosition : LightType::Area),
          shape_(shape), prim_(prim), Lemit_(std::move(Lemit)), twoSided_(twoSided),
          alpha_(type() == LightType::Area ? shape->alpha.get() : nullptr), image_(std::move(image)) {}

    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const override;
    float pdfLi(const LightSampleContext& ctx, Vec3 wi, const SurfaceInteraction* hit) const override;
    std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const override;
    void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const override;
    Spectrum L(Vec3 p, Vec3 n, Vec2 uv, Vec3 w, const SampledWavelengths* lambda) const override {
        if (!twoSided_ && dot(n, w) < 0) return {};
        if (alpha_ && !alpha_->keepsPoint(p, n, uv)) return {};
        if (!image_) return Lemit_(lambda);
        // The image's RGB lifted per lookup as an illuminant (pbrt-v4's RGBIlluminantSpectrum);
        // Lemit is then the scale alone, whose RGB is grey.
        return lambda ? liftIlluminant(image_->at(uv), *lambda) * Lemit_.rgb().g : Lemit_.rgb() * image_->at(uv);
    }
    // With an image, its mean radiance (pbrt-v4's, which ignores how uv stretches).
    // The primitive's box and normal cone; light leaves up to pi/2 from the normal.
    std::optional<LightBounds> bounds() const override;
    Spectrum phi() const override {
        return (image_ ? Lemit_.rgb() * image_->mean() : Lemit_.rgb()) * (kPi * (twoSided_ ? 2.0f : 1.0f) * shape_->area(prim_));
    }

private:
    // sampleLe's solid-angle density of a direction at cosine c to the oriented normal.
    float emittedDirectionPdf(float c) const {
        return twoSided_ ? 0.5f * std::fabs(c) * kInvPi : cosineHemispherePdf(c);
    }

    const Shape* shape_;
    int prim_;
    LightSpectrum Lemit_;
    bool twoSided_;
    const AlphaMask* alpha_;  // the shape's, or null
    std::shared_ptr<const EmissionImage> image_;  // null: uniform radiance
};

}  // namespace ps
