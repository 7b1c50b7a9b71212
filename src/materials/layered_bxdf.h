// pbrt-v4's layered BxDFs (coateddiffuse, coatedconductor): a dielectric coating over an
// opaque base (Lambertian or conductor), separated by a slab of homogeneous medium of the
// given thickness (sigma_t = 1 per unit thickness, single-scattering albedo, Henyey-
// Greenstein g). Both faces are coated (two-sided): a wo below the surface is mirrored.
//
// There is no closed form, so f() and pdf() are stochastic estimates from nSamples random
// walks between the two interfaces (the position-free layered model of Guo et al. 2018),
// with next-event estimation through the exit interface, MIS-weighted against sampling the
// interface (thesis §9.2, power heuristic). Their random numbers come from an Rng seeded by
// a hash of (wo, wi), so both are deterministic functions of their arguments. sample()
// follows one physical walk; its f/pdf ratio is right but pdf is only proportional to the
// true density (pdfIsProportional), so MIS must call pdf().
//
// Bottom must be a reflection-only BxDF with non-virtual-call access (a final class held by
// value, so calls devirtualise on the hot path).
#pragma once
#include <limits>
#include "materials/conductor_bxdf.h"
#include "materials/dielectric_bxdf.h"
#include "materials/diffuse_bxdf.h"

namespace ps {

struct LayerParams {
    float thickness = 0.01f;  // in units of the mean free path (sigma_t = 1)
    Spectrum albedo;          // single-scattering albedo inside the slab; black: no scattering
    float g = 0;              // Henyey-Greenstein asymmetry
    int maxDepth = 10;        // scattering events per walk
    int nSamples = 1;         // walks per evaluation of f() and pdf()
    // pbrt-v4's MIS weight for leaving through a rough coating along a direction sampled at
    // the base or in the medium uses the density of the reverse sampling, so f() is biased
    // high against sample() (measured with a white diffuse base: +2% of the albedo at
    // coating alpha 0.05, +8% at 0.3, +11% at 0.7).
    // false (the default) gives the consistent estimator, so path tracing, light tracing and
    // BDPT agree; true reproduces pbrt-v4's images of rough coatings.
    bool pbrtExitMis = false;
};

template <typename Bottom>
class LayeredBxDF final : public BxDF {
public:
    LayeredBxDF(const DielectricBxDF& top, const Bottom& bottom, const LayerParams& p)
        : top_(top), bottom_(bottom), p_(p) {
        p_.thickness = std::max(p_.thickness, std::numeric_limits<float>::min());
        p_.nSamples = std::max(1, p_.nSamples);
        p_.maxDepth = std::max(0, p_.maxDepth);
    }

    uint8_t flags() const override;
    Spectrum f(Vec3 wo, Vec3 wi, TransportMode mode) const override;
    std::optional<BSDFSample> sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const override;
    float pdf(Vec3 wo, Vec3 wi, TransportMode mode) const override;
    bool stochastic() const override { return true; }
    float coatingMirrorReflectance(Vec3 wo) const override {
        const uint8_t top = top_.flags();
        return (top & kSpecular) && (top & kReflection) ? fresnelDielectric(std::fabs(wo.z), top_.eta()) : 0.0f;
    }
    bool specularThroughCoating() const override {
        // A base of specular lobes only; a black one (flags() 0: no lobe) reflects nothing.
        const uint8_t bottom = bottom_.flags();
        return (top_.flags() & kSpecular) && (bottom & kSpecular) && !(bottom & (kDiffuse | kGlossy));
    }

private:
    // Density with which NEE through the coating would produce the inside direction wInside
    // for the exit direction wi (the MIS partner of sampling wInside at the base or medium).
    float exitNeePdf(Vec3 wInside, Vec3 wi, TransportMode mode) const;
    // Transmittance of the slab over a height difference dz along w (Beer-Lambert).
    static float Tr(float dz, Vec3 w) {
        if (std::fabs(dz) <= std::numeric_limits<float>::min()) return 1;
        return std::exp(-std::fabs(dz / w.z));
    }

    DielectricBxDF top_;
    Bottom bottom_;
    LayerParams p_;
};

using CoatedDiffuseBxDF = LayeredBxDF<DiffuseBxDF>;
using CoatedConductorBxDF = LayeredBxDF<ConductorBxDF>;

extern template class LayeredBxDF<DiffuseBxDF>;
extern template class LayeredBxDF<ConductorBxDF>;

}  // namespace ps
