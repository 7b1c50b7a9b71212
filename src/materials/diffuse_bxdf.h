// Lambertian reflection f = R/pi, sampled by the cosine-weighted hemisphere on wo's side.
#pragma once
#include "materials/bxdf.h"
#include "math/warp.h"

namespace ps {

class DiffuseBxDF final : public BxDF {
public:
    explicit DiffuseBxDF(const Spectrum& R) : BxDF(false), R_(R) {}
    uint8_t flags() const override { return R_.isBlack() ? 0 : (kReflection | kDiffuse); }
    Spectrum f(Vec3 wo, Vec3 wi, TransportMode) const override {
        return sameHemisphere(wo, wi) ? R_ * kInvPi : Spectrum();
    }
    std::optional<BSDFSample> sample(Vec3 wo, float, Vec2 u, TransportMode) const override {
        Vec3 wi = sampleCosineHemisphere(u);
        if (wo.z < 0) wi.z = -wi.z;
        float pdf = cosineHemispherePdf(absCosTheta(wi));
        if (!(pdf > 0)) return std::nullopt;
        return BSDFSample{R_ * kInvPi, wi, pdf, kReflection | kDiffuse, 1};
    }
    float pdf(Vec3 wo, Vec3 wi, TransportMode) const override {
        return sameHemisphere(wo, wi) ? cosineHemispherePdf(absCosTheta(wi)) : 0.0f;
    }
    BxDFEval evaluate(Vec3 wo, Vec3 wi, TransportMode) const override {
        if (!sameHemisphere(wo, wi)) return {};
        return {R_ * kInvPi, absCosTheta(wi) * kInvPi, absCosTheta(wo) * kInvPi};
    }

private:
    Spectrum R_;
};

}  // namespace ps
