// Metals: specular or Torrance-Sparrow microfacet reflection with the complex Fresnel term.
#pragma once
#include "materials/bxdf.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"

namespace ps {

class ConductorBxDF final : public BxDF {
public:
    ConductorBxDF(const TrowbridgeReitz& d, const Spectrum& eta, const Spectrum& k)
        : BxDF(false), distrib_(d), eta_(eta), k_(k) {}
    uint8_t flags() const override { return kReflection | (distrib_.effectivelySmooth() ? kSpecular : kGlossy); }
    Spectrum f(Vec3 wo, Vec3 wi, TransportMode mode) const override;
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const override;
    float pdf(Vec3 wo, Vec3 wi, TransportMode mode) const override;

private:
    TrowbridgeReitz distrib_;
    Spectrum eta_, k_;
};

}  // namespace ps
