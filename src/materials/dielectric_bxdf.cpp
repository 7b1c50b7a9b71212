#include "materials/dielectric_bxdf.h"

namespace ps {

namespace {

// The generalised half vector of Walter et al. (eq. 16), oriented to +z; false if degenerate
// or back-facing.
bool halfVector(Vec3 wo, Vec3 wi, float eta, Vec3& wm, float& etap, bool& reflect) {
    float cosO = cosTheta(wo), cosI = cosTheta(wi);
    reflect = cosO * cosI > 0;
    etap = reflect ? 1.0f : (cosO > 0 ? eta : 1 / eta);
    wm = wi * etap + wo;
    if (cosI == 0 || cosO == 0 || lengthSquared(wm) == 0) return false;
    wm = faceForward(normalize(wm), Vec3(0, 0, 1));
    // Microfacets seen from behind contribute nothing.
    return !(dot(wm, wi) * cosI < 0 || dot(wm, wo) * cosO < 0);
}

}  // namespace

Spectrum DielectricBxDF::f(Vec3 wo, Vec3 wi, TransportMode mode) const {
    if (eta_ == 1 || distrib_.effectivelySmooth()) return {};
    Vec3 wm;
    float etap;
    bool reflect;
    if (!halfVector(wo, wi, eta_, wm, etap, reflect)) return {};
    float F = fresnelDielectric(dot(wo, wm), eta_);
    float cosO = cosTheta(wo), cosI = cosTheta(wi);
    if (reflect) return Spectrum(distrib_.D(wm) * distrib_.G(wo, wi) * F / std::fabs(4 * cosI * cosO));
    float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap) * cosI * cosO;
    float ft = distrib_.D(wm) * (1 - F) * distrib_.G(wo, wi) * std::fabs(dot(wi, wm) * dot(wo, wm) / denom);
    if (mode == TransportMode::Radiance) ft /= sqr(etap);
    return Spectrum(ft);
}

float DielectricBxDF::pdf(Vec3 wo, Vec3 wi, TransportMode, uint8_t lobes) const {
    if (eta_ == 1 || distrib_.effectivelySmooth()) return 0;
    Vec3 wm;
    float etap;
    bool reflect;
    if (!halfVector(wo, wi, eta_, wm, etap, reflect)) return 0;
    float R = fresnelDielectric(dot(wo, wm), eta_), T = 1 - R;
    if (!(lobes & kReflection)) R = 0;
    if (!(lobes & kTransmission)) T = 0;
    if (R + T == 0) return 0;
    if (reflect) return distrib_.pdf(wo, wm) / (4 * absDot(wo, wm)) * R / (R + T);
    float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap);
    float dwmDwi = absDot(wi, wm) / denom;
    return distrib_.pdf(wo, wm) * dwmDwi * T / (R + T);
}

std::optional<BSDFSample> DielectricBxDF::sample(Vec3 wo, float uc, Vec2 u, TransportMode mode, uint8_t lobes) const {
    if (eta_ == 1) {
        if (!(lobes & kTransmission)) return std::nullopt;
        float c = absCosTheta(wo);
        if (c == 0) return std::nullopt;
        return BSDFSample{Spectrum(1 / c), -wo, 1, kTransmission | kSpecular, 1};
    }
    if (distrib_.effectivelySmooth()) {
        float R = fresnelDielectric(cosTheta(wo), eta_), T = 1 - R;
        if (!(lobes & kReflection)) R = 0;
        if (!(lobes & kTransmission)) T = 0;
        if (R + T == 0) return std::nullopt;
        if (uc < R / (R + T)) {
            Vec3 wi(-wo.x, -wo.y, wo.z);
            return BSDFSample{Spectrum(R / absCosTheta(wi)), wi, R / (R + T), kReflection | kSpecular, 1};
        }
        Vec3 wi;
        float etap;
        if (!refract(wo, Vec3(0, 0, 1), eta_, &etap, &wi) || wi.z == 0) return std::nullopt;
        float ft = T / absCosTheta(wi);
        if (mode == TransportMode::Radiance) ft /= sqr(etap);
        return BSDFSample{Spectrum(ft), wi, T / (R + T), kTransmission | kSpecular, etap};
    }
    if (wo.z == 0) return std::nullopt;
    Vec3 wm = distrib_.sampleVisibleNormal(wo, u);  // upper hemisphere
    float R = fresnelDielectric(dot(wo, wm), eta_), T = 1 - R;
    if (!(lobes & kReflection)) R = 0;
    if (!(lobes & kTransmission)) T = 0;
    if (R + T == 0) return std::nullopt;
    float cosO = cosTheta(wo);
    if (uc < R / (R + T)) {
        Vec3 wi = reflect(wo, wm);
        if (!sameHemisphere(wo, wi)) return std::nullopt;
        float pdf = distrib_.pdf(wo, wm) / (4 * absDot(wo, wm)) * R / (R + T);
        float f = distrib_.D(wm) * distrib_.G(wo, wi) * R / std::fabs(4 * cosTheta(wi) * cosO);
        if (!(pdf > 0)) return std::nullopt;
        return BSDFSample{Spectrum(f), wi, pdf, kReflection | kGlossy, 1};
    }
    Vec3 wi;
    float etap;
    if (!refract(wo, wm, eta_, &etap, &wi)) return std::nullopt;
    if (sameHemisphere(wo, wi) || wi.z == 0) return std::nullopt;
    float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap);
    float dwmDwi = absDot(wi, wm) / denom;
    float pdf = distrib_.pdf(wo, wm) * dwmDwi * T / (R + T);
    float ft = T * distrib_.D(wm) * distrib_.G(wo, wi) * std::fabs(dot(wi, wm) * dot(wo, wm) / (cosTheta(wi) * cosO * denom));
    if (mode == TransportMode::Radiance) ft /= sqr(etap);
    if (!(pdf > 0)) return std::nullopt;
    return BSDFSample{Spectrum(ft), wi, pdf, kTransmission | kGlossy, etap};
}

}  // namespace ps
