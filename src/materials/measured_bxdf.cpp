#include "materials/measured_bxdf.h"

#include <cmath>

#include "materials/fresnel.h"
#include "spectral/sampled_spectrum.h"

namespace ps {

namespace {

// The unit square's coordinates of spherical angles, and back (the files' parameterisation:
// theta by its square root, so the pole region gets fewer cells).
float thetaToU(float theta) { return std::sqrt(theta * (2 / kPi)); }
float phiToU(float phi) { return phi * (1 / (2 * kPi)) + 0.5f; }
float uToTheta(float u) { return u * u * (kPi / 2); }
float uToPhi(float u) { return (2 * u - 1) * kPi; }

// Solid-angle density from the unit square's density at wm: dw = 2 pi^2 u sin(theta) du,
// times the reflection's 4 (wo . wm); bounded below as pbrt-v4 does at the pole.
float jacobian(float uTheta, float sinThetaM, float woDotWm) {
    return 4 * woDotWm * std::max(2 * kPi * kPi * uTheta * sinThetaM, 1e-6f);
}

}  // namespace

Spectrum MeasuredBxDF::reflectance(Vec2 ui, const float* woParams, Vec2 uWm, Vec2 uWo, float cosI) const {
    const MeasuredBRDF& b = *brdf_;
    Spectrum r;
    if (spectral_ && b.hasSpectra) {
        for (int i = 0; i < kWavelengthSamples; ++i) {
            float p[3] = {woParams[0], woParams[1], lambda_[i]};
            r[i] = std::max(0.0f, b.spectra.evaluate(ui, p));
        }
    } else {
        for (int c = 0; c < 3; ++c) {
            float p[3] = {woParams[0], woParams[1], float(c)};
            r[c] = std::max(0.0f, b.rgb.evaluate(ui, p));
        }
        r.c3 = r.g;  // the RGB invariant (math/spectrum.h)
        if (spectral_) {
            SampledWavelengths w;
            w.lambda = lambda_;
            r = liftUnbounded(r, w);
        }
    }
    float scale = b.ndf.evaluate(uWm) / (4 * b.sigma.evaluate(uWo) * cosI);
    if (!std::isfinite(scale) || scale < 0) return {};
    return r * scale;
}

void MeasuredBxDF::fAndPdf(Vec3 wo, Vec3 wi, Spectrum* f, float* pdf) const {
    if (f) *f = {};
    if (pdf) *pdf = 0;
    Vec3 wm = wi + wo;
    if (lengthSquared(wm) == 0 || wi.z <= 0) return;
    wm = normalize(wm);
    const MeasuredBRDF& b = *brdf_;
    float thetaO = safeAcos(wo.z), phiO = std::atan2(wo.y, wo.x);
    float thetaM = safeAcos(wm.z), phiM = std::atan2(wm.y, wm.x);
    float param[2] = {phiO, thetaO};
    Vec2 uWm(thetaToU(thetaM), phiToU(b.isotropic ? phiM - phiO : phiM));
    uWm.y -= std::floor(uWm.y);
    PiecewiseLinear2D::Result ui = b.vndf.invert(uWm, param);
    if (f) *f = reflectance(ui.p, param, uWm, Vec2(thetaToU(thetaO), phiToU(phiO)), wi.z);
    if (pdf) {
        float sinThetaM = std::sqrt(wm.x * wm.x + wm.y * wm.y);
        float p = ui.pdf * b.luminance.evaluate(ui.p, param) / jacobian(uWm.x, sinThetaM, dot(wo, wm));
        *pdf = std::isfinite(p) && p > 0 ? p : 0;
    }
}

Spectrum MeasuredBxDF::f(Vec3 wo, Vec3 wi, TransportMode) const {
    if (!sameHemisphere(wo, wi)) return {};
    if (wo.z < 0) wo = -wo, wi = -wi;
    Spectrum f;
    fAndPdf(wo, wi, &f, nullptr);
    return f;
}

float MeasuredBxDF::pdf(Vec3 wo, Vec3 wi, TransportMode) const {
    if (!sameHemisphere(wo, wi)) return 0;
    if (wo.z < 0) wo = -wo, wi = -wi;
    float p;
    fAndPdf(wo, wi, nullptr, &p);
    return p;
}

BxDFEval MeasuredBxDF::evaluate(Vec3 wo, Vec3 wi, TransportMode) const {
    if (!sameHemisphere(wo, wi)) return {};
    if (wo.z < 0) wo = -wo, wi = -wi;
    BxDFEval e;
    fAndPdf(wo, wi, &e.f, &e.pdfFwd);
    fAndPdf(wi, wo, nullptr, &e.pdfRev);
    return e;
}

std::optional<BSDFSample> MeasuredBxDF::sample(Vec3 wo, float, Vec2 u, TransportMode) const {
    const bool flip = wo.z <= 0;
    if (flip) wo = -wo;
    const MeasuredBRDF& b = *brdf_;
    float thetaO = safeAcos(wo.z), phiO = std::atan2(wo.y, wo.x);
    float param[2] = {phiO, thetaO};
    // Luminance warp, then the visible normals: u -> ui -> wm.
    PiecewiseLinear2D::Result ui = b.luminance.sample(u, param);
    PiecewiseLinear2D::Result m = b.vndf.sample(ui.p, param);
    Vec2 uWm = m.p;
    float phiM = uToPhi(uWm.y) + (b.isotropic ? phiO : 0), thetaM = uToTheta(uWm.x);
    float sinThetaM = std::sin(thetaM), cosThetaM = std::cos(thetaM);
    Vec3 wm(sinThetaM * std::cos(phiM), sinThetaM * std::sin(phiM), cosThetaM);
    Vec3 wi = reflect(wo, wm);
    if (wi.z <= 0) return std::nullopt;
    Spectrum f = reflectance(ui.p, param, uWm, Vec2(thetaToU(thetaO), phiToU(phiO)), wi.z);
    float pdf = m.pdf * ui.pdf / jacobian(uWm.x, sinThetaM, dot(wo, wm));
    if (!(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
    if (flip) wi = -wi;
    return BSDFSample{f, wi, pdf, kReflection | kGlossy, 1};
}

}  // namespace ps
