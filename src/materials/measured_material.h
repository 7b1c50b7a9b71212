// `Material "measured"`: a measured BRDF file; no textures, so in RGB mode one BxDF serves
// every hit; in spectral mode each hit builds one at its path's wavelengths.
#pragma once
#include "materials/material.h"
#include "materials/measured_bxdf.h"

namespace ps {

class MeasuredMaterial final : public Material {
public:
    explicit MeasuredMaterial(std::shared_ptr<const MeasuredBRDF> brdf) : brdf_(brdf) {
        constant_ = std::make_unique<MeasuredBxDF>(std::move(brdf));
    }
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override {
        if (!ctx.lambda) return constant_.get();
        return buf.alloc<MeasuredBxDF>(brdf_.get(), *ctx.lambda);
    }

private:
    std::shared_ptr<const MeasuredBRDF> brdf_;
};

}  // namespace ps
