#include "materials/beam_diffusion.h"

#include <algorithm>
#include <cmath>

#include "materials/fresnel.h"
#include "materials/phase_function.h"
#include "math/catmull_rom.h"

namespace ps {

namespace {

constexpr int kDepthSamples = 100;  // stratified depths along the beam, as pbrt-v4
constexpr int kRhoSamples = 100, kRadiusSamples = 64;

// The depth with exponential CDF 1 - exp(-sigma z) at u (inverse transform).
double exponentialDepth(double u, double sigma) { return -std::log(1 - u) / sigma; }

}  // namespace

double fresnelMoment1(double eta) {
    const double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
    if (eta < 1) return 0.45966 - 1.73965 * eta + 3.37668 * e2 - 3.904945 * e3 + 2.49277 * e4 - 0.68441 * e5;
    return -4.61686 + 11.1136 * eta - 10.4646 * e2 + 5.11455 * e3 - 1.27198 * e4 + 0.12746 * e5;
}

double fresnelMoment2(double eta) {
    const double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
    if (eta < 1) return 0.27614 - 0.87350 * eta + 1.12077 * e2 - 0.65095 * e3 + 0.07883 * e4 + 0.04860 * e5;
    const double r = 1 / eta, r2 = r * r, r3 = r2 * r;
    return -547.033 + 45.3087 * r3 - 218.725 * r2 + 458.843 * r + 404.557 * eta - 189.519 * e2 + 54.9327 * e3 -
           9.00603 * e4 + 0.63942 * e5;
}

// Real sources along the refracted beam at depths drawn by the reduced extinction, each
// mirrored as a negative source above the extrapolated boundary z_e (the dipole); the
// exitance combines fluence and flux by the Fresnel moments (Kienle-Patterson boundary), and
// kappa removes what single scattering already counts near the entry point.
double beamDiffusionMultiple(double sigmaS, double sigmaA, double g, double eta, double r) {
    const double sigmapS = sigmaS * (1 - g), sigmapT = sigmaA + sigmapS, rhop = sigmapS / sigmapT;
    const double D = (2 * sigmaA + sigmapS) / (3 * sigmapT * sigmapT);  // Grosjean
    const double sigmaTr = std::sqrt(std::max(0.0, sigmaA / D));
    const double fm1 = fresnelMoment1(eta), fm2 = fresnelMoment2(eta);
    const double ze = -2 * D * (1 + 3 * fm2) / (1 - 2 * fm1);
    const double cPhi = 0.25 * (1 - 2 * fm1), cE = 0.5 * (1 - 3 * fm2);
    double sum = 0;
    for (int i = 0; i < kDepthSamples; ++i) {
        const double zr = exponentialDepth((i + 0.5) / kDepthSamples, sigmapT), zv = -zr + 2 * ze;
        const double dr = std::sqrt(r * r + zr * zr), dv = std::sqrt(r * r + zv * zv);
        const double er = std::exp(-sigmaTr * dr), ev = std::exp(-sigmaTr * dv);
        const double fluence = kInv4Pi / D * (er / dr - ev / dv);
        const double flux = kInv4Pi * (zr * (1 + sigmaTr * dr) * er / (dr * dr * dr) - zv * (1 + sigmaTr * dv) * ev / (dv * dv * dv));
        const double kappa = 1 - std::exp(-2 * sigmapT * (dr + zr));
        sum += kappa * rhop * rhop * (fluence * cPhi + flux * cE);
    }
    return sum / kDepthSamples;
}

// Single scattering from points on the refracted beam (normal incidence) that reach the
// surface at distance r below the critical angle, through the phase function and the
// boundary's Fresnel transmission.
double beamDiffusionSingle(double sigmaS, double sigmaA, double g, double eta, double r) {
    const double sigmaT = sigmaA + sigmaS, rho = sigmaS / sigmaT;
    const double tCrit = r * std::sqrt(std::max(0.0, eta * eta - 1));
    double sum = 0;
    for (int i = 0; i < kDepthSamples; ++i) {
        const double t = tCrit + exponentialDepth((i + 0.5) / kDepthSamples, sigmaT);
        const double d = std::sqrt(r * r + t * t), cosO = t / d;
        sum += rho * std::exp(-sigmaT * (d + tCrit)) / (d * d) * henyeyGreenstein(float(cosO), float(g)) *
               (1 - fresnelDielectric(float(-cosO), float(eta))) * std::fabs(cosO);
    }
    return sum / kDepthSamples;
}

EffectiveAlbedoTable effectiveAlbedoTable(float g, float eta) {
    EffectiveAlbedoTable t;
    std::vector<float> radius(kRadiusSamples);
    radius[0] = 0;
    radius[1] = 2.5e-3f;
    for (int i = 2; i < kRadiusSamples; ++i) radius[i] = radius[i - 1] * 1.2f;
    t.rho.resize(kRhoSamples);
    t.rhoEff.resize(kRhoSamples);
    std::vector<float> profile(kRadiusSamples);
    for (int i = 0; i < kRhoSamples; ++i) {
        const double rho = (1 - std::exp(-8.0 * i / (kRhoSamples - 1))) / (1 - std::exp(-8.0));
        t.rho[i] = float(rho);
        // The radial profile 2 pi r R(r), whose integral over r is the total reflectance.
        for (int j = 0; j < kRadiusSamples; ++j) {
            const double r = radius[j];
            profile[j] = float(2 * kPi * r *
                               (beamDiffusionSingle(rho, 1 - rho, g, eta, r) + beamDiffusionMultiple(rho, 1 - rho, g, eta, r)));
        }
        t.rhoEff[i] = integrateCatmullRom(radius, profile);
    }
    return t;
}

float albedoForReflectance(const EffectiveAlbedoTable& table, float reflectance) {
    return invertCatmullRom(table.rho, table.rhoEff, std::clamp(reflectance, 0.0f, 1.0f));
}

}  // namespace ps
