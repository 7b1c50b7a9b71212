// Dielectric interfaces: smooth (specular reflection and refraction chosen by Fresnel) and
// rough (Walter et al. 2007 microfacet reflection and transmission). eta is the index of
// the side opposite the normal relative to the side it points into. Refracted radiance is
// scaled by 1/eta'^2 only when transporting radiance: the adjoint BSDF for importance
// omits it (thesis §5.2, non-symmetric scattering under refraction).
#pragma once
#include "materials/bxdf.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"

namespace ps {

class DielectricBxDF final : public BxDF {
public:
    DielectricBxDF(float eta, const TrowbridgeReitz& d) : eta_(eta), distrib_(d) {}
    uint8_t flags() const override {
        uint8_t f = eta_ == 1 ? kTransmission : (kReflection | kTransmission);
        return f | (distrib_.effectivelySmooth() ? kSpecular : kGlossy);
    }
    Spectrum f(Vec3 wo, Vec3 wi, TransportMode mode) const override;
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const override {
        return sample(wo, uc, u, mode, kReflection | kTransmission);
    }
    float pdf(Vec3 wo, Vec3 wi, TransportMode mode) const override { return pdf(wo, wi, mode, kReflection | kTransmission); }
    // Restricted to the lobes in `lobes` (kReflection, kTransmission), as layered BxDFs need.
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode, uint8_t lobes) const;
    float pdf(Vec3 wo, Vec3 wi, TransportMode mode, uint8_t lobes) const;

private:
    float eta_;
    TrowbridgeReitz distrib_;
};

// A thin slab: inter-reflections inside summed in closed form, transmission straight through.
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
