// pbrt-v4's materials (PBRT-CONVENTIONS §5): each evaluates its textures at the shading
// point and builds its BxDF in the scratch buffer.
#pragma once
#include <array>
#include <memory>
#include <optional>
#include "materials/layered_bxdf.h"
#include "materials/material.h"
#include "spectral/spectrum_source.h"

namespace ps {

using FloatTex = std::shared_ptr<FloatTexture>;
using SpectrumTex = std::shared_ptr<SpectrumTexture>;

// A dielectric's index of refraction: a constant, or in spectral mode a spectrum of which
// the path follows its first wavelength only (pbrt-v4's dispersion: the secondary
// wavelengths are terminated where the index is evaluated, since each would refract
// differently). RGB mode uses `value`.
struct IndexOfRefraction {
    float value = 1.5f;
    std::optional<SpectrumSource> dispersive;
    float evaluate(const TextureEvalContext& ctx) const;
};

// Anisotropic roughness as the scene gives it: alpha = sqrt(roughness) unless remap is off.
struct Roughness {
    FloatTex u, v;
    bool remap = true;
    Vec2 alpha(const TextureEvalContext& ctx) const;
};

class DiffuseMaterial final : public Material {
public:
    explicit DiffuseMaterial(SpectrumTex R);
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override;

private:
    SpectrumTex R_;
};

class ConductorMaterial final : public Material {
public:
    // Either eta and k, or reflectance (then eta = 1 and k follows from it).
    ConductorMaterial(SpectrumTex eta, SpectrumTex k, SpectrumTex reflectance, Roughness r)
        : eta_(std::move(eta)), k_(std::move(k)), reflectance_(std::move(reflectance)), rough_(std::move(r)) {}
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override;

private:
    SpectrumTex eta_, k_, reflectance_;
    Roughness rough_;
};

class DielectricMaterial final : public Material {
public:
    DielectricMaterial(IndexOfRefraction eta, Roughness r) : eta_(std::move(eta)), rough_(std::move(r)) {}
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override;

private:
    IndexOfRefraction eta_;
    Roughness rough_;
};

class ThinDielectricMaterial final : public Material {
public:
    explicit ThinDielectricMaterial(IndexOfRefraction eta) : eta_(std::move(eta)) {}
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override;

private:
    IndexOfRefraction eta_;
};

class DiffuseTransmissionMaterial final : public Material {
public:
    DiffuseTransmissionMaterial(SpectrumTex R, SpectrumTex T, float scale) : R_(std::move(R)), T_(std::move(T)), scale_(scale) {}
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override;

private:
    SpectrumTex R_, T_;
    float scale_;
};

// Shared by the layered materials; defaults as in pbrt-v4.
struct LayerTextures {
    FloatTex thickness, g;    // 0.01, 0
    SpectrumTex albedo;       // 0: no scattering inside the layer
    int maxDepth = 10, nSamples = 1;
    LayerParams evaluate(const TextureEvalContext& ctx) const;
};

struct CoatedDiffuseParams {
    SpectrumTex reflectance;  // of the Lambertian base
    Roughness roughness;      // of the coating
    IndexOfRefraction eta;    // of the coating
    LayerTextures layer;
};

class CoatedDiffuseMaterial final : public Material {
public:
    explicit CoatedDiffuseMaterial(CoatedDiffuseParams p) : p_(std::move(p)) {}
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override;
    bool stochasticBxDF() const override { return true; }

private:
    CoatedDiffuseParams p_;
};

struct CoatedConductorParams {
    Roughness interfaceRoughness;
    IndexOfRefraction interfaceEta;
    // The base: eta and k, or reflectance (as for ConductorMaterial).
    SpectrumTex conductorEta, conductorK, reflectance;
    Roughness conductorRoughness;
    LayerTextures layer;
};

// A conductor under a dielectric coating; the conductor's eta and k are taken relative to
// the coating's index.
class CoatedConductorMaterial final : public Material {
public:
    explicit CoatedConductorMaterial(CoatedConductorParams p) : p_(std::move(p)) {}
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override;
    bool stochasticBxDF() const override { return true; }

private:
    CoatedConductorParams p_;
};

// Chooses materials[1] with probability `amount`, by a deterministic hash of (p, wo).
class MixMaterial final : public Material {
public:
    MixMaterial(std::array<std::shared_ptr<Material>, 2> m, FloatTex amount) : m_(std::move(m)), amount_(std::move(amount)) {
        needsDerivatives_ = m_[0]->needsShadingDerivatives() || m_[1]->needsShadingDerivatives();
    }
    const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const override { return resolve(ctx)->bxdf(ctx, buf); }
    const Material* resolve(const MaterialEvalContext& ctx) const override;
    bool stochasticBxDF() const override { return m_[0]->stochasticBxDF() || m_[1]->stochasticBxDF(); }

private:
    std::array<std::shared_ptr<Material>, 2> m_;
    FloatTex amount_;
};

// No surface: the ray continues as if nothing was there (used to bound media in pbrt).
class InterfaceMaterial final : public Material {
public:
    const BxDF* bxdf(const MaterialEvalContext&, ScratchBuffer&) const override { return nullptr; }
    bool isInterface() const override { return true; }
};

}  // namespace ps
