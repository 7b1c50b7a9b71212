// pbrt-v4's thindielectric: a thin parallel slab whose internal inter-reflections are summed
// in closed form (geometric series R' = R + T^2 R / (1 - R^2)); transmitted light leaves
// undeviated (wi = -wo), so there is no 1/eta^2 radiance scaling.
#pragma once
#include "materials/bxdf.h"
#include "materials/fresnel.h"

namespace ps {

class ThinDielectricBxDF final : public BxDF {
public:
    explicit ThinDielectricBxDF(float eta) : eta_(eta) {}
    uint8_t flags() const override { return kReflection | kTransmission | kSpecular; }
    Spectrum f(Vec3, Vec3, TransportMode) const override { return {}; }
    float pdf(Vec3, Vec3, TransportMode) const override { return 0; }
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2, TransportMode) const override {
        float R = fresnelDielectric(absCosTheta(wo), eta_), T = 1 - R;
        if (R < 1) {
            R += T * T * R / (1 - R * R);
            T = 1 - R;
        }
        float c = absCosTheta(wo);
        if (c == 0) return std::nullopt;
        if (uc < R / (R + T)) return BSDFSample{Spectrum(R / c), Vec3(-wo.x, -wo.y, wo.z), R / (R + T), kReflection | kSpecular, 1};
        return BSDFSample{Spectrum(T / c), -wo, T / (R + T), kTransmission | kSpecular, 1};
    }

private:
    float eta_;
};

}  // namespace ps
