// pbrt-v4's "hair" material: the hair BSDF (hair_bxdf.h) with its absorption given directly
// (sigma_a), by the colour it should have (reflectance) or by melanin concentrations, and the
// offset h across the fibre from the hit's v (h = -1 + 2 v, as pbrt-v4 does on every shape).
// In spectral mode every absorption is at the path's wavelengths (pbrt-v4's GetBxDF).
#pragma once
#include "materials/materials.h"

namespace ps {

struct HairTextures {
    // Exactly one of these decides sigma_a (pbrt-v4's precedence is applied when parsing):
    // sigmaA, else reflectance, else the concentrations (an absent one counts as 0).
    SpectrumTex sigmaA, reflectance;
    FloatTex eumelanin, pheomelanin;
    FloatTex eta, betaM, betaN, alpha;  // 1.55, 0.3, 0.3, 2 degrees
};

class HairMaterial final : public Material {
public:
    explicit HairMaterial(HairTextures t) : t_(std::move(t)) {}
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override;

private:
    HairTextures t_;
};

}  // namespace ps
