#include "materials/materials.h"

#include <cstring>

#include "materials/coated_diffuse_bxdf.h"
#include "materials/conductor_bxdf.h"
#include "materials/dielectric_bxdf.h"
#include "materials/diffuse_bxdf.h"
#include "mc/rng.h"

namespace ps {

Vec2 Roughness::alpha(const TextureEvalContext& ctx) const {
    float ur = u->evaluate(ctx), vr = v->evaluate(ctx);
    if (remap) return {TrowbridgeReitz::roughnessToAlpha(ur), TrowbridgeReitz::roughnessToAlpha(vr)};
    return {std::max(0.0f, ur), std::max(0.0f, vr)};
}

const BxDF* DiffuseMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    return buf.alloc<DiffuseBxDF>(clamp(R_->evaluate(ctx), 0, 1));
}

const BxDF* ConductorMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    Vec2 a = rough_.alpha(ctx);
    Spectrum eta, k;
    if (reflectance_) {
        // Normal-incidence reflectance r with eta = 1: k = 2 sqrt(r) / sqrt(1 - r).
        Spectrum r = clamp(reflectance_->evaluate(ctx), 0, 0.9999f);
        eta = Spectrum(1.0f);
        k = Spectrum(2 * std::sqrt(r.r) / std::sqrt(1 - r.r), 2 * std::sqrt(r.g) / std::sqrt(1 - r.g),
                     2 * std::sqrt(r.b) / std::sqrt(1 - r.b));
    } else {
        eta = eta_->evaluate(ctx);
        k = k_->evaluate(ctx);
    }
    return buf.alloc<ConductorBxDF>(TrowbridgeReitz(a.x, a.y), eta, k);
}

const BxDF* DielectricMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    Vec2 a = rough_.alpha(ctx);
    return buf.alloc<DielectricBxDF>(eta_, TrowbridgeReitz(a.x, a.y));
}

const BxDF* ThinDielectricMaterial::bxdf(const MaterialEvalContext&, ScratchBuffer& buf) const {
    return buf.alloc<ThinDielectricBxDF>(eta_);
}

const BxDF* DiffuseTransmissionMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    return buf.alloc<DiffuseTransmissionBxDF>(clamp(R_->evaluate(ctx) * scale_, 0, 1), clamp(T_->evaluate(ctx) * scale_, 0, 1));
}

const BxDF* CoatedDiffuseMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    Vec2 a = p_.roughness.alpha(ctx);
    CoatedDiffuseBxDF::Params q;
    q.reflectance = clamp(p_.reflectance->evaluate(ctx), 0, 1);
    q.albedo = clamp(p_.albedo->evaluate(ctx), 0, 1);
    q.thickness = std::max(p_.thickness->evaluate(ctx), std::numeric_limits<float>::min());
    q.g = clampf(p_.g->evaluate(ctx), -0.99f, 0.99f);
    q.eta = p_.eta;
    q.maxDepth = p_.maxDepth;
    q.nSamples = p_.nSamples;
    return buf.alloc<CoatedDiffuseBxDF>(q, TrowbridgeReitz(a.x, a.y));
}

const Material* MixMaterial::resolve(const MaterialEvalContext& ctx) const {
    float amount = amount_->evaluate(ctx);
    const Material* chosen;
    if (amount <= 0) {
        chosen = m_[0].get();
    } else if (amount >= 1) {
        chosen = m_[1].get();
    } else {
        uint64_t h = 0;
        float v[6] = {ctx.p.x, ctx.p.y, ctx.p.z, ctx.wo.x, ctx.wo.y, ctx.wo.z};
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
