// pbrt-v4's coateddiffuse: a dielectric coating over a Lambertian base with a thin absorbing
// slab between them, both faces coated. f and pdf are stochastic estimates from random walks
// between the two interfaces (Guo et al. 2018 as formulated in pbrt-v4), with next-event
// estimation through the exit interface; the walk's random numbers are a hash of (wo, wi),
// so f is a deterministic function of its arguments.
#pragma once
#include "materials/dielectric_bxdf.h"
#include "materials/diffuse_bxdf.h"

namespace ps {

class CoatedDiffuseBxDF final : public BxDF {
public:
    struct Params {
        Spectrum reflectance{0.5f}, albedo;
        float thickness = 0.01f, g = 0, eta = 1.5f;
        int maxDepth = 10, nSamples = 1;
    };
    CoatedDiffuseBxDF(const Params& p, const TrowbridgeReitz& d) : p_(p), top_(p.eta, d), bottom_(p.reflectance) {}

    uint8_t flags() const override;
    Spectrum f(Vec3 wo, Vec3 wi, TransportMode mode) const override;
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const override;
    float pdf(Vec3 wo, Vec3 wi, TransportMode mode) const override;

private:
    // Transmittance of the slab along w.
    float Tr(Vec3 w) const {
        if (std::fabs(p_.thickness) <= std::numeric_limits<float>::min()) return 1;
        return std::exp(-std::fabs(p_.thickness / w.z));
    }
    Params p_;
    DielectricBxDF top_;
    DiffuseBxDF bottom_;
};

}  // namespace ps
