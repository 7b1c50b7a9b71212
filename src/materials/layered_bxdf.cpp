#include "materials/layered_bxdf.h"

#include <cstring>

#include "materials/phase_function.h"
#include "mc/mis.h"
#include "mc/rng.h"

namespace ps {

namespace {

uint64_t hashFloats(const float* v, int n) {
    uint64_t h = 0x6a09e667f3bcc909ULL;
    for (int i = 0; i < n; ++i) {
        uint32_t bits;
        std::memcpy(&bits, &v[i], sizeof bits);
        h = hashCombine(h, bits);
    }
    return h;
}
uint64_t hashVec(Vec3 w) {
    float v[3] = {w.x, w.y, w.z};
    return hashFloats(v, 3);
}

bool usable(const std::optional<BSDFSample>& s) { return s && !s->f.isBlack() && s->pdf > 0 && s->wi.z != 0; }

// Uniform numbers for one walk; pairs are drawn in a fixed order (argument evaluation order
// is unspecified in C++, and f must not depend on the compiler).
struct WalkRng {
    Rng rng;
    WalkRng(uint64_t a, uint64_t b) : rng(a, b) {}
    float operator()() { return rng.uniform(); }
    Vec2 pair() {
        float a = rng.uniform();
        float b = rng.uniform();
        return {a, b};
    }
};

// Distance in z to the next collision along w: free paths are exponential with sigma_t = 1.
float sampleFreeFlightDz(float u, Vec3 w) { return -std::log1p(-u) * absCosTheta(w); }

}  // namespace

template <typename Bottom>
uint8_t LayeredBxDF<Bottom>::flags() const {
    uint8_t topF = top_.flags(), botF = bottom_.flags();
    uint8_t fl = kReflection;  // the base is opaque
    if (topF & kSpecular) fl |= kSpecular;
    if ((topF & kDiffuse) || (botF & kDiffuse) || !p_.albedo.isBlack())
        fl |= kDiffuse;
    else if ((topF & kGlossy) || (botF & kGlossy))
        fl |= kGlossy;
    return fl;
}

template <typename Bottom>
float LayeredBxDF<Bottom>::exitNeePdf(Vec3 wInside, Vec3 wi, TransportMode mode) const {
    // NEE draws the inside direction from wi (adjoint mode): its density is pdf(wi -> wInside).
    // pbrt-v4 evaluates the reverse, pdf(wInside -> wi), which differs across a refraction,
    // so its two weights do not sum to one (see LayerParams::pbrtExitMis).
    if (p_.pbrtExitMis) return top_.pdf(wInside, wi, mode, kTransmission);
    return top_.pdf(wi, wInside, adjoint(mode), kTransmission);
}

template <typename Bottom>
Spectrum LayeredBxDF<Bottom>::f(Vec3 wo, Vec3 wi, TransportMode mode) const {
    if (wo.z < 0) {  // two-sided: mirror to the upper side
        wo = -wo;
        wi = -wi;
    }
    // Light entering through the top can leave only through the top: the base is opaque.
    if (!sameHemisphere(wo, wi)) return {};
    const float thick = p_.thickness, exitZ = thick;
    const int n = p_.nSamples;
    const bool topSpecular = top_.flags() & kSpecular, bottomSpecular = bottom_.flags() & kSpecular;
    const bool scatters = !p_.albedo.isBlack();
    const HGPhaseFunction phase(p_.g);

    Spectrum f = top_.f(wo, wi, mode) * float(n);  // reflection off the coating itself
    WalkRng r(hashVec(wo), hashVec(wi));
    for (int s = 0; s < n; ++s) {
        // Enter through the coating along a sampled refraction of wo.
        float uc = r();
        auto wos = top_.sample(wo, uc, r.pair(), mode, kTransmission);
        if (!usable(wos)) continue;
        // Refraction of wi into the slab, traced backwards (adjoint mode): the fixed exit
        // direction for next-event estimation.
        uc = r();
        auto wis = top_.sample(wi, uc, r.pair(), adjoint(mode), kTransmission);
        if (!usable(wis)) continue;

        Spectrum beta = wos->f * (absCosTheta(wos->wi) / wos->pdf);
        float z = thick;
        Vec3 w = wos->wi;
        for (int depth = 0; depth < p_.maxDepth; ++depth) {
            if (depth > 3 && beta.maxComponent() < 0.25f) {  // Russian roulette
                float q = std::max(0.0f, 1 - beta.maxComponent());
                if (r() < q) break;
                beta /= 1 - q;
            }
            if (!scatters) {
                z = (z == thick) ? 0 : thick;
                beta *= Tr(thick, w);
            } else {
                float zp = z + (w.z > 0 ? 1 : -1) * sampleFreeFlightDz(r(), w);
                if (zp == z) continue;
                if (0 < zp && zp < thick) {
                    // Scattering in the medium: NEE out through the coating along wis...
                    float wt = topSpecular ? 1 : powerHeuristic(wis->pdf, phase.pdf(-w, -wis->wi));
                    f += beta * p_.albedo * wis->f * (phase.p(-w, -wis->wi) * wt * Tr(zp - exitZ, wis->wi) / wis->pdf);
                    // ...then continue in a direction drawn from the phase function (p/pdf = 1).
                    float phPdf = 0;
                    Vec3 wNew = phase.sample(-w, r.pair(), &phPdf);
                    if (!(phPdf > 0) || wNew.z == 0) continue;
                    beta *= p_.albedo;
                    w = wNew;
                    z = zp;
                    // Heading for the coating: it may leave towards wi (MIS with the NEE above).
                    if (w.z > 0 && !topSpecular) {
                        Spectrum fExit = top_.f(-w, wi, mode);
                        if (!fExit.isBlack()) {
                            float exitPdf = exitNeePdf(-w, wi, mode);
                            f += beta * fExit * (Tr(zp - exitZ, w) * powerHeuristic(phPdf, exitPdf));
                        }
                    }
                    continue;
                }
                z = clampf(zp, 0, thick);
            }

            if (z == exitZ) {
                // At the coating from inside: transmission out is counted by NEE; follow the
                // internal reflection.
                uc = r();
                auto bs = top_.sample(-w, uc, r.pair(), mode, kReflection);
                if (!usable(bs)) break;
                beta *= bs->f * (absCosTheta(bs->wi) / bs->pdf);
                w = bs->wi;
                continue;
            }
            // At the base: NEE towards wis, then scatter.
            if (!bottomSpecular) {
                float wt = topSpecular ? 1 : powerHeuristic(wis->pdf, bottom_.pdf(-w, -wis->wi, mode));
                f += beta * bottom_.f(-w, -wis->wi, mode) * wis->f *
                     (absCosTheta(wis->wi) * wt * Tr(thick, wis->wi) / wis->pdf);
            }
            uc = r();
            auto bs = bottom_.sample(-w, uc, r.pair(), mode);
            if (!usable(bs)) break;
            beta *= bs->f * (absCosTheta(bs->wi) / bs->pdf);
            w = bs->wi;
            // The sampled direction may leave through a rough coating towards wi.
            if (!topSpecular) {
                Spectrum fExit = top_.f(-w, wi, mode);
                if (!fExit.isBlack()) {
                    float wt = 1;
                    if (!bottomSpecular) wt = powerHeuristic(bs->pdf, exitNeePdf(-w, wi, mode));
                    f += beta * fExit * (Tr(thick, bs->wi) * wt);
                }
            }
        }
    }
    return f / float(n);
}

template <typename Bottom>
std::optional<BSDFSample> LayeredBxDF<Bottom>::sample(Vec3 wo, float uc, Vec2 u, TransportMode mode) const {
    const bool flip = wo.z < 0;
    if (flip) wo = -wo;
    auto bs = top_.sample(wo, uc, u, mode);
    if (!usable(bs)) return std::nullopt;
    if (bs->isReflection()) {
        if (flip) bs->wi = -bs->wi;
        bs->pdfIsProportional = true;
        return bs;
    }
    const float thick = p_.thickness;
    const bool scatters = !p_.albedo.isBlack();
    const HGPhaseFunction phase(p_.g);
    float uv[3] = {uc, u.x, u.y};
    WalkRng r(hashVec(wo), hashFloats(uv, 3));

    // Path throughput numerator and density, kept apart so the pdf can be reported.
    Spectrum f = bs->f * absCosTheta(bs->wi);
    float pdf = bs->pdf;
    bool specularPath = bs->isSpecular();
    Vec3 w = bs->wi;
    float z = thick;
    for (int depth = 0; depth < p_.maxDepth; ++depth) {
        float rrBeta = f.maxComponent() / pdf;
        if (depth > 3 && rrBeta < 0.25f) {
            float q = std::max(0.0f, 1 - rrBeta);
            if (r() < q) return std::nullopt;
            pdf *= 1 - q;
        }
        if (w.z == 0) return std::nullopt;
        if (scatters) {
            float zp = z + (w.z > 0 ? 1 : -1) * sampleFreeFlightDz(r(), w);
            if (zp == z) return std::nullopt;
            if (0 < zp && zp < thick) {
                float phPdf = 0;
                Vec3 wNew = phase.sample(-w, r.pair(), &phPdf);
                if (!(phPdf > 0) || wNew.z == 0) return std::nullopt;
                f *= p_.albedo * phPdf;
                pdf *= phPdf;
                specularPath = false;
                w = wNew;
                z = zp;
                continue;
            }
            z = clampf(zp, 0, thick);
        } else {
            z = (z == thick) ? 0 : thick;
            f *= Tr(thick, w);
        }
        float uc2 = r();
        Vec2 u2 = r.pair();
        auto s = z == 0 ? bottom_.sample(-w, uc2, u2, mode) : top_.sample(-w, uc2, u2, mode);
        if (!usable(s)) return std::nullopt;
        f *= s->f;
        pdf *= s->pdf;
        specularPath &= s->isSpecular();
        w = s->wi;
        if (s->isTransmission()) {
            // Out through the coating (the base is opaque): a reflection of the whole layer.
            uint8_t fl = uint8_t((sameHemisphere(wo, w) ? kReflection : kTransmission) | (specularPath ? kSpecular : kGlossy));
            if (flip) w = -w;
            BSDFSample out{f, w, pdf, fl, 1};
            out.pdfIsProportional = true;
            return out;
        }
        f *= absCosTheta(s->wi);
    }
    return std::nullopt;
}

template <typename Bottom>
float LayeredBxDF<Bottom>::pdf(Vec3 wo, Vec3 wi, TransportMode mode) const {
    if (wo.z < 0) {
        wo = -wo;
        wi = -wi;
    }
    const int n = p_.nSamples;
    float pdfSum = 0;
    if (sameHemisphere(wo, wi)) {
        // Approximation used by pbrt-v4: reflection at the coating plus the
        // transmit-reflect-transmit paths, ignoring longer ones.
        const bool topSpecular = !(top_.flags() & (kDiffuse | kGlossy));
        const bool bottomSpecular = !(bottom_.flags() & (kDiffuse | kGlossy));
        pdfSum = float(n) * top_.pdf(wo, wi, mode, kReflection);
        WalkRng r(hashVec(wi), hashVec(wo));
        for (int s = 0; s < n; ++s) {
            float uc = r();
            auto wos = top_.sample(wo, uc, r.pair(), mode, kTransmission);
            uc = r();
            auto wis = top_.sample(wi, uc, r.pair(), adjoint(mode), kTransmission);
            if (!wos || wos->f.isBlack() || !(wos->pdf > 0) || !wis || wis->f.isBlack() || !(wis->pdf > 0)) continue;
            if (topSpecular) {
                pdfSum += bottom_.pdf(-wos->wi, -wis->wi, mode);
                continue;
            }
            uc = r();
            auto rs = bottom_.sample(-wos->wi, uc, r.pair(), mode);
            if (!rs || rs->f.isBlack() || !(rs->pdf > 0)) continue;
            if (bottomSpecular) {
                pdfSum += top_.pdf(-rs->wi, wi, mode);
                continue;
            }
            // Both rough: MIS of the two ways of reaching wi (the TRT pdf product).
            float rPdf = bottom_.pdf(-wos->wi, -wis->wi, mode);
            pdfSum += powerHeuristic(wis->pdf, rPdf) * rPdf;
            float tPdf = top_.pdf(-rs->wi, wi, mode);
            pdfSum += powerHeuristic(rs->pdf, tPdf) * tPdf;
        }
    }
    // Mixed with a uniform density so that it is never zero where f might not be.
    return lerp(0.9f, 1 / (4 * kPi), pdfSum / float(n));
}

template class LayeredBxDF<DiffuseBxDF>;
template class LayeredBxDF<ConductorBxDF>;

}  // namespace ps
