#include "materials/materials.h"

#include <cmath>
#include <cstring>

#include "materials/conductor_bxdf.h"
#include "materials/dielectric_bxdf.h"
#include "materials/diffuse_bxdf.h"
#include "materials/diffuse_transmission_bxdf.h"
#include "materials/layered_bxdf.h"
#include "materials/spectral_textures.h"
#include "materials/textures.h"
#include "materials/thin_dielectric_bxdf.h"
#include "mc/rng.h"
#include "spectral/wavelengths.h"

namespace ps {

namespace {

TrowbridgeReitz distribution(const Roughness& r, const TextureEvalContext& ctx) {
    Vec2 a = r.alpha(ctx);
    return TrowbridgeReitz(a.x, a.y);
}

// Complex index of a conductor: eta + i k, or from a normal-incidence reflectance r with
// eta = 1, where F(0) = k^2 / (4 + k^2) = r gives k = 2 sqrt(r) / sqrt(1 - r). r is kept
// below 1 so k stays finite.
void conductorIndex(const SpectrumTex& etaTex, const SpectrumTex& kTex, const SpectrumTex& reflectance,
                    const TextureEvalContext& ctx, Spectrum& eta, Spectrum& k) {
    if (!reflectance) {
        eta = etaTex->evaluate(ctx);
        k = kTex->evaluate(ctx);
        return;
    }
    Spectrum r = clamp(reflectance->evaluate(ctx), 0, 0.9999f);
    eta = Spectrum(1.0f);
    for (int c = 0; c < 4; ++c) k[c] = 2 * std::sqrt(r[c]) / std::sqrt(1 - r[c]);  // every channel: rgb or wavelengths
}

}  // namespace

float IndexOfRefraction::evaluate(const TextureEvalContext& ctx) const {
    if (!ctx.lambda || !dispersive) return value;
    ctx.lambda->terminateSecondary();
    const float eta = dispersive->at(ctx.lambda->lambda[0]);
    return eta > 0 && std::isfinite(eta) ? eta : 1.0f;
}

Vec2 Roughness::alpha(const TextureEvalContext& ctx) const {
    float ur = u->evaluate(ctx), vr = v->evaluate(ctx);
    if (remap) return {TrowbridgeReitz::roughnessToAlpha(ur), TrowbridgeReitz::roughnessToAlpha(vr)};
    return {std::max(0.0f, ur), std::max(0.0f, vr)};
}

LayerParams LayerTextures::evaluate(const TextureEvalContext& ctx) const {
    LayerParams p;
    p.thickness = thickness->evaluate(ctx);
    p.albedo = clamp(albedo->evaluate(ctx), 0, 1);
    p.g = clampf(g->evaluate(ctx), -1, 1);
    p.maxDepth = maxDepth;
    p.nSamples = nSamples;
    return p;
}

DiffuseMaterial::DiffuseMaterial(SpectrumTex R) : R_(std::move(R)) {
    if (auto rgb = constantRGB(*R_)) constant_ = std::make_unique<DiffuseBxDF>(clamp(*rgb, 0, 1));
}

const BxDF* DiffuseMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    return buf.alloc<DiffuseBxDF>(clamp(R_->evaluate(ctx), 0, 1));
}

const BxDF* ConductorMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    Spectrum eta, k;
    conductorIndex(eta_, k_, reflectance_, ctx, eta, k);
    return buf.alloc<ConductorBxDF>(distribution(rough_, ctx), eta, k);
}

const BxDF* DielectricMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    return buf.alloc<DielectricBxDF>(eta_.evaluate(ctx), distribution(rough_, ctx));
}

const BxDF* ThinDielectricMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    return buf.alloc<ThinDielectricBxDF>(eta_.evaluate(ctx));
}

const BxDF* DiffuseTransmissionMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    return buf.alloc<DiffuseTransmissionBxDF>(clamp(R_->evaluate(ctx) * scale_, 0, 1), clamp(T_->evaluate(ctx) * scale_, 0, 1));
}

const BxDF* CoatedDiffuseMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    DielectricBxDF top(p_.eta.evaluate(ctx), distribution(p_.roughness, ctx));
    DiffuseBxDF bottom(clamp(p_.reflectance->evaluate(ctx), 0, 1));
    return buf.alloc<CoatedDiffuseBxDF>(top, bottom, p_.layer.evaluate(ctx));
}

const BxDF* CoatedConductorMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    const float interfaceEta = p_.interfaceEta.evaluate(ctx);
    DielectricBxDF top(interfaceEta, distribution(p_.interfaceRoughness, ctx));
    Spectrum eta, k;
    conductorIndex(p_.conductorEta, p_.conductorK, p_.reflectance, ctx, eta, k);
    // The base sits in the coating, not in vacuum: its index is relative to the coating's.
    ConductorBxDF bottom(distribution(p_.conductorRoughness, ctx), eta / interfaceEta, k / interfaceEta);
    return buf.alloc<CoatedConductorBxDF>(top, bottom, p_.layer.evaluate(ctx));
}

const Material* MixMaterial::resolve(const MaterialEvalContext& ctx) const {
    float amount = amount_->evaluate(ctx);
    const Material* chosen;
    if (amount <= 0) {
        chosen = m_[0].get();
    } else if (amount >= 1) {
        chosen = m_[1].get();
    } else {
        // A deterministic choice per (point, direction), so that f and pdf evaluations at
        // the same vertex agree (as pbrt-v4's MixMaterial::ChooseMaterial).
        uint64_t h = 0;
        const float v[6] = {ctx.p.x, ctx.p.y, ctx.p.z, ctx.wo.x, ctx.wo.y, ctx.wo.z};
        for (float f : v) {
            uint32_t bits;
            std::memcpy(&bits, &f, 4);
            h = hashCombine(h, bits);
        }
        float u = float(h >> 40) * 0x1p-24f;
        chosen = amount < u ? m_[0].get() : m_[1].get();
    }
    return chosen->resolve(ctx);
}

}  // namespace ps
