// pbrt-v4's "diffuse" area light: constant radiance over one primitive of a shape,
// one-sided (the side of the oriented normal) unless twosided.
#pragma once
#include "geometry/shape.h"
#include "lights/light.h"
#include "math/warp.h"

namespace ps {

class DiffuseAreaLight final : public Light {
public:
    DiffuseAreaLight(const Shape* shape, int prim, Spectrum Lemit, bool twoSided)
        : Light(LightType::Area), shape_(shape), prim_(prim), Lemit_(Lemit), twoSided_(twoSided) {}

    std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const override;
    float pdfLi(const LightSampleContext& ctx, Vec3 wi, const SurfaceInteraction* hit) const override;
    std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir) const override;
    void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const override;
    Spectrum L(Vec3 p, Vec3 n, Vec2 uv, Vec3 w) const override {
        (void)p; (void)uv;
        if (!twoSided_ && dot(n, w) < 0) return {};
        return Lemit_;
    }
    Spectrum phi() const override { return Lemit_ * (kPi * (twoSided_ ? 2.0f : 1.0f) * shape_->area(prim_)); }

private:
    // sampleLe's solid-angle density of a direction at cosine c to the oriented normal.
    float emittedDirectionPdf(float c) const {
        return twoSided_ ? 0.5f * std::fabs(c) * kInvPi : cosineHemispherePdf(c);
    }

    const Shape* shape_;
    int prim_;
    Spectrum Lemit_;
    bool twoSided_;
};

}  // namespace ps
