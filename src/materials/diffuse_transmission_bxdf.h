// Diffuse reflection R/pi on wo's side and diffuse transmission T/pi to the other side
// (pbrt-v4's diffusetransmission). The lobe is chosen by the ratio of max(R) to max(T).
#pragma once
#include "materials/bxdf.h"
#include "math/warp.h"

namespace ps {

class DiffuseTransmissionBxDF final : public BxDF {
public:
    DiffuseTransmissionBxDF(const Spectrum& R, const Spectrum& T) : R_(R), T_(T) {}
    uint8_t flags() const override {
        return (R_.isBlack() ? 0 : kReflection | kDiffuse) | (T_.isBlack() ? 0 : kTransmission | kDiffuse);
    }
    Spectrum f(Vec3 wo, Vec3 wi, TransportMode) const override { return (sameHemisphere(wo, wi) ? R_ : T_) * kInvPi; }
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode) const override {
        float pr = R_.maxComponent(), pt = T_.maxComponent();
        if (pr + pt <= 0) return std::nullopt;
        Vec3 wi = sampleCosineHemisphere(u);
        bool reflectLobe = uc < pr / (pr + pt);
        // Reflection stays on wo's side, transmission crosses to the other.
        if ((wo.z < 0) == reflectLobe) wi.z = -wi.z;
        float pdf = cosineHemispherePdf(absCosTheta(wi)) * (reflectLobe ? pr : pt) / (pr + pt);
        if (!(pdf > 0)) return std::nullopt;
        return BSDFSample{(reflectLobe ? R_ : T_) * kInvPi, wi, pdf,
                          uint8_t((reflectLobe ? kReflection : kTransmission) | kDiffuse), 1};
    }
    float pdf(Vec3 wo, Vec3 wi, TransportMode) const override {
        float pr = R_.maxComponent(), pt = T_.maxComponent();
        if (pr + pt <= 0) return 0;
        bool same = sameHemisphere(wo, wi);
        return cosineHemispherePdf(absCosTheta(wi)) * (same ? pr : pt) / (pr + pt);
    }

private:
    Spectrum R_, T_;
};

}  // namespace ps
