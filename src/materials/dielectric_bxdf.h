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
        // eta = 1 is a pass-through whatever the roughness: one specular transmission.
        if (eta_ == 1) return kTransmission | kSpecular;
        return kReflection | kTransmission | (distrib_.effectivelySmooth() ? kSpecular : kGlossy);
    }
    Spectrum f(Vec3 wo, Vec3 wi, TransportMode mode) const override;
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const override {
        return sample(wo, uc, u, mode, kReflection | kTransmission);
    }
    float pdf(Vec3 wo, Vec3 wi, TransportMode mode) const override { return pdf(wo, wi, mode, kReflection | kTransmission); }
    float eta() const { return eta_; }
    // Restricted to the lobes in `lobes` (kReflection, kTransmission), as layered BxDFs need.
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode, uint8_t lobes) const;
    float pdf(Vec3 wo, Vec3 wi, TransportMode mode, uint8_t lobes) const;

private:
    float eta_;
    TrowbridgeReitz distrib_;
};

}  // namespace ps
