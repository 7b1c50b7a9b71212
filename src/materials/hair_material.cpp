#include "materials/hair_material.h"

#include <algorithm>
#include <cmath>

#include "materials/hair_bxdf.h"

namespace ps {

namespace {

// A textured value that is not finite becomes `fallback`: the BSDF must never see NaN.
float finiteOr(float v, float fallback) { return std::isfinite(v) ? v : fallback; }

}  // namespace

const BxDF* HairMaterial::bxdf(const MaterialEvalContext& ctx, ScratchBuffer& buf) const {
    HairParams p;
    // pbrt-v4 clamps the roughnesses to [0.01, 1]; the index is kept in a range where the
    // Fresnel terms stay finite (pbrt-v4 takes it as given).
    p.betaM = std::clamp(finiteOr(t_.betaM->evaluate(ctx), 0.3f), 0.01f, 1.0f);
    p.betaN = std::clamp(finiteOr(t_.betaN->evaluate(ctx), 0.3f), 0.01f, 1.0f);
    p.alphaDegrees = finiteOr(t_.alpha->evaluate(ctx), 0);
    p.eta = std::clamp(finiteOr(t_.eta->evaluate(ctx), 1.55f), 1e-3f, 1e3f);
    if (t_.sigmaA) {
        p.sigmaA = clamp(t_.sigmaA->evaluate(ctx), 0, INFINITY);
    } else if (t_.reflectance) {
        p.sigmaA = HairBxDF::sigmaAFromReflectance(clamp(t_.reflectance->evaluate(ctx), 0, 1), p.betaN);
    } else {
        float ce = t_.eumelanin ? std::max(0.0f, t_.eumelanin->evaluate(ctx)) : 0.0f;
        float cp = t_.pheomelanin ? std::max(0.0f, t_.pheomelanin->evaluate(ctx)) : 0.0f;
        p.sigmaA = HairBxDF::sigmaAFromConcentration(finiteOr(ce, 0), finiteOr(cp, 0), ctx.lambda);
    }
    p.spectral = ctx.lambda != nullptr;
    // Outside [0, 1] (a mesh's own uv) v is clamped; pbrt-v4 requires it there.
    p.h = std::clamp(-1 + 2 * finiteOr(ctx.uv.y, 0.5f), -1.0f, 1.0f);
    p.fibre = ctx.fibre;
    return buf.alloc<HairBxDF>(p);
}

}  // namespace ps
