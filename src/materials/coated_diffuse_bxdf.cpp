#include "materials/coated_diffuse_bxdf.h"

#include <cstring>

#include "mc/rng.h"
#include "mc/mis.h"

namespace ps {

namespace {

uint64_t hashVec(Vec3 v) {
    uint32_t b[3];
    std::memcpy(b, &v, sizeof b);
    return hashCombine(hashCombine(mix64(b[0]), b[1]), b[2]);
}

TransportMode adjoint(TransportMode m) {
    return m == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
}

}  // namespace

uint8_t CoatedDiffuseBxDF::flags() const {
    uint8_t f = kReflection | kDiffuse;
    if (top_.flags() & kSpecular) f |= kSpecular;
    return f;
}

Spectrum CoatedDiffuseBxDF::f(Vec3 wo, Vec3 wi, TransportMode mode) const {
    // Two-sided: work as if wo were on the top side.
    if (wo.z < 0) {
        wo = -wo;
        wi = -wi;
    }
    if (!sameHemisphere(wo, wi)) return {};  // an opaque base transmits nothing
    const int n = p_.nSamples;
    Spectrum f = top_.f(wo, wi, mode) * float(n);  // reflection at the coating itself
    Rng rng(hashVec(wo), hashVec(wi));
    auto r = [&] { return rng.uniform(); };
    const bool topSpecular = (top_.flags() & kSpecular) != 0;
    for (int s = 0; s < n; ++s) {
        auto wos = top_.sample(wo, r(), {r(), r()}, mode, kTransmission);
        if (!wos || wos->f.isBlack() || !(wos->pdf > 0) || wos->wi.z == 0) continue;
        // The exit direction wi, sampled backwards through the coating, for NEE at the base.
        auto wis = top_.sample(wi, r(), {r(), r()}, adjoint(mode), kTransmission);
        if (!wis || wis->f.isBlack() || !(wis->pdf > 0) || wis->wi.z == 0) continue;
        Spectrum beta = wos->f * (absCosTheta(wos->wi) / wos->pdf);
        bool atBottom = false;  // we start just under the top interface, travelling down
        Vec3 w = wos->wi;
        for (int depth = 0; depth < p_.maxDepth; ++depth) {
            if (depth > 3 && beta.maxComponent() < 0.25f) {
                float q = std::max(0.0f, 1 - beta.maxComponent());
                if (r() < q) break;
                beta /= 1 - q;
            }
            atBottom = !atBottom;  // cross the slab
            beta *= Tr(w);
            if (!atBottom) {
                // At the coating from inside: reflect back down (transmission exits, counted by NEE).
                auto bs = top_.sample(-w, r(), {r(), r()}, mode, kReflection);
                if (!bs || bs->f.isBlack() || !(bs->pdf > 0) || bs->wi.z == 0) break;
                beta *= bs->f * (absCosTheta(bs->wi) / bs->pdf);
                w = bs->wi;
                continue;
            }
            // At the diffuse base: next-event estimation out through the coating along wi.
            float wt = 1;
            if (!topSpecular) wt = powerHeuristic(wis->pdf, bottom_.pdf(-w, -wis->wi, mode));
            f += beta * bottom_.f(-w, -wis->wi, mode) * (absCosTheta(wis->wi) * wt * Tr(wis->wi)) * wis->f / wis->pdf;
            // Scatter off the base.
            auto bs = bottom_.sample(-w, r(), {r(), r()}, mode);
            if (!bs || bs->f.isBlack() || !(bs->pdf > 0) || bs->wi.z == 0) break;
            beta *= bs->f * (absCosTheta(bs->wi) / bs->pdf);
            w = bs->wi;
            if (!topSpecular) {
                // The sampled direction may leave through a rough coating towards wi: MIS it.
                Spectrum fExit = top_.f(-w, wi, mode);
                if (!fExit.isBlack()) {
                    float exitPdf = top_.pdf(-w, wi, mode, kTransmission);
                    float wt2 = powerHeuristic(bs->pdf, exitPdf);
                    f += beta * Tr(bs->wi) * fExit * wt2;
                }
            }
        }
    }
    return f / float(n);
}

std::optional<BSDFSample> CoatedDiffuseBxDF::sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const {
    bool flip = wo.z < 0;
    if (flip) wo = -wo;
    auto bs = top_.sample(wo, uc, u, mode);
    if (!bs || bs->f.isBlack() || !(bs->pdf > 0) || bs->wi.z == 0) return std::nullopt;
    if (bs->isReflection()) {
        if (flip) bs->wi = -bs->wi;
        bs->pdfIsProportional = true;
        return bs;
    }
    Vec3 w = bs->wi;
    bool specularPath = bs->isSpecular();
    Spectrum f = bs->f * absCosTheta(bs->wi);
    float pdf = bs->pdf;
    bool atBottom = false;
    Rng rng(hashVec(wo), hashVec(Vec3(uc, u.x, u.y)));
    auto r = [&] { return rng.uniform(); };
    for (int depth = 0; depth < p_.maxDepth; ++depth) {
        float rrBeta = f.maxComponent() / pdf;
        if (depth > 3 && rrBeta < 0.25f) {
            float q = std::max(0.0f, 1 - rrBeta);
            if (r() < q) return std::nullopt;
            pdf *= 1 - q;
        }
        if (w.z == 0) return std::nullopt;
        atBottom = !atBottom;
        f *= Tr(w);
        std::optional<BSDFSample> s = atBottom ? bottom_.sample(-w, r(), {r(), r()}, mode) : top_.sample(-w, r(), {r(), r()}, mode);
        if (!s || s->f.isBlack() || !(s->pdf > 0) || s->wi.z == 0) return std::nullopt;
        f *= s->f;
        pdf *= s->pdf;
        specularPath &= s->isSpecular();
        w = s->wi;
        if (s->isTransmission()) {
            // Left through the coating: a reflection of the layered surface as a whole.
            uint8_t fl = uint8_t(kReflection | (specularPath ? kSpecular : kGlossy));
            if (flip) w = -w;
            BSDFSample out{f, w, pdf, fl, 1};
            out.pdfIsProportional = true;
            return out;
        }
        f *= absCosTheta(s->wi);
    }
    return std::nullopt;
}

float CoatedDiffuseBxDF::pdf(Vec3 wo, Vec3 wi, TransportMode mode) const {
    if (wo.z < 0) {
        wo = -wo;
        wi = -wi;
    }
    Rng rng(hashVec(wi), hashVec(wo));
    auto r = [&] { return rng.uniform(); };
    const int n = p_.nSamples;
    float pdfSum = 0;
    if (sameHemisphere(wo, wi)) {
        pdfSum += float(n) * top_.pdf(wo, wi, mode, kReflection);
        for (int s = 0; s < n; ++s) {
            // Transmission down, diffuse reflection at the base, transmission up.
            auto wos = top_.sample(wo, r(), {r(), r()}, mode, kTransmission);
            auto wis = top_.sample(wi, r(), {r(), r()}, adjoint(mode), kTransmission);
            if (!wos || !(wos->pdf > 0) || !wis || !(wis->pdf > 0)) continue;
            if (top_.flags() & kSpecular) {
                pdfSum += bottom_.pdf(-wos->wi, -wis->wi, mode);
                continue;
            }
            auto rs = bottom_.sample(-wos->wi, r(), {r(), r()}, mode);
            if (!rs || !(rs->pdf > 0)) continue;
            float rPdf = bottom_.pdf(-wos->wi, -wis->wi, mode);
            pdfSum += powerHeuristic(wis->pdf, rPdf) * rPdf;
            float tPdf = top_.pdf(-rs->wi, wi, mode, kReflection | kTransmission);
            pdfSum += powerHeuristic(rs->pdf, tPdf) * tPdf;
        }
    }
    // Blend with a uniform density so the estimate is never zero where f is not.
    return lerp(0.9f, 1 / (4 * kPi), pdfSum / float(n));
}

}  // namespace ps
