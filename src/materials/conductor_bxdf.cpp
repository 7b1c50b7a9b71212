#include "materials/conductor_bxdf.h"

namespace ps {

Spectrum ConductorBxDF::f(Vec3 wo, Vec3 wi, TransportMode) const {
    if (!sameHemisphere(wo, wi) || distrib_.effectivelySmooth()) return {};
    float cosO = absCosTheta(wo), cosI = absCosTheta(wi);
    if (cosO == 0 || cosI == 0) return {};
    Vec3 wm = wi + wo;
    if (lengthSquared(wm) == 0) return {};
    wm = normalize(wm);
    Spectrum F = fresnelComplex(absDot(wo, wm), eta_, k_);
    return F * (distrib_.D(wm) * distrib_.G(wo, wi) / (4 * cosI * cosO));
}

std::optional<BSDFSample> ConductorBxDF::sample(Vec3 wo, float, Vec2 u, TransportMode) const {
    if (distrib_.effectivelySmooth()) {
        Vec3 wi(-wo.x, -wo.y, wo.z);
        float c = absCosTheta(wi);
        if (c == 0) return std::nullopt;
        return BSDFSample{fresnelComplex(c, eta_, k_) / c, wi, 1, kReflection | kSpecular, 1};
    }
    if (wo.z == 0) return std::nullopt;
    Vec3 woUp = wo.z < 0 ? -wo : wo;  // the distribution is symmetric; sample on +z
    Vec3 wm = distrib_.sampleVisibleNormal(woUp, u);
    if (wo.z < 0) wm = -wm;
    Vec3 wi = reflect(wo, wm);
    if (!sameHemisphere(wo, wi)) return std::nullopt;
    float pdf = distrib_.pdf(wo, wm) / (4 * absDot(wo, wm));
    float cosO = absCosTheta(wo), cosI = absCosTheta(wi);
    if (!(pdf > 0) || cosI == 0) return std::nullopt;
    Spectrum F = fresnelComplex(absDot(wo, wm), eta_, k_);
    Spectrum f = F * (distrib_.D(wm) * distrib_.G(wo, wi) / (4 * cosI * cosO));
    return BSDFSample{f, wi, pdf, kReflection | kGlossy, 1};
}

float ConductorBxDF::pdf(Vec3 wo, Vec3 wi, TransportMode) const {
    if (!sameHemisphere(wo, wi) || distrib_.effectivelySmooth()) return 0;
    Vec3 wm = wo + wi;
    if (lengthSquared(wm) == 0) return 0;
    wm = normalize(wm);
    // D(w, wm) depends only on |cos| terms, so either orientation of wm gives the same value.
    return distrib_.pdf(wo, wm) / (4 * absDot(wo, wm));
}

}  // namespace ps
