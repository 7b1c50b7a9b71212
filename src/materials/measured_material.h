// `Material "measured"`: a measured BRDF file; no textures, so one BxDF serves every hit.
#pragma once
#include "materials/material.h"
#include "materials/measured_bxdf.h"

namespace ps {

class MeasuredMaterial final : public Material {
public:
    explicit MeasuredMaterial(std::shared_ptr<const MeasuredBRDF> brdf) { constant_ = std::make_unique<MeasuredBxDF>(std::move(brdf)); }
    const BxDF* bxdf(const MaterialEvalContext&, ScratchBuffer&) const override { return constant_.get(); }
    const char* rgbOnly() const override { return "measured"; }  // RGB tables of the measured spectra
};

}  // namespace ps
