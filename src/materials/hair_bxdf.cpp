#include "materials/hair_bxdf.h"

#include <algorithm>
#include <cmath>

#include "materials/fresnel.h"
#include "math/bessel.h"
#include "spectral/sampled_spectrum.h"

namespace ps {

namespace {

constexpr double kPiD = M_PI;

double clampd(double v, double lo, double hi) { return std::min(hi, std::max(lo, v)); }
double safeSqrtD(double v) { return std::sqrt(std::max(0.0, v)); }

// Longitudinal lobe of variance v (d'Eon et al. 2011), normalised so that its integral
// against cos(theta_i) d theta_i is 1. Narrow lobes (v <= 0.1) in logarithms, where I0 and
// sinh overflow; there 1/sinh(1/v) is 2 e^{-1/v} to far below double precision. Evaluated in
// double: for v ~ 1e-5 the exponent is a difference of numbers ~1e5.
double Mp(double cosThetaI, double cosThetaO, double sinThetaI, double sinThetaO, double v) {
    const double a = cosThetaI * cosThetaO / v, b = sinThetaI * sinThetaO / v;
    if (v <= 0.1) return std::exp(logBesselI0(a) - b - 1 / v + std::log(2.0) + std::log(1 / (2 * v)));
    return std::exp(-b) * besselI0(a) / (std::sinh(1 / v) * 2 * v);
}

double logisticCdf(double x, double s) { return 1 / (1 + std::exp(-x / s)); }

// The logistic density of scale s restricted to [-pi, pi] and renormalised.
double trimmedLogistic(double x, double s) {
    const double e = std::exp(-std::fabs(x) / s);
    return e / (s * (1 + e) * (1 + e)) / (logisticCdf(kPiD, s) - logisticCdf(-kPiD, s));
}

double sampleTrimmedLogistic(double u, double s) {
    const double lo = logisticCdf(-kPiD, s), hi = logisticCdf(kPiD, s);
    u = lo + u * (hi - lo);
    if (!(u > 0)) return -kPiD;
    if (!(u < 1)) return kPiD;
    return clampd(-s * std::log(1 / u - 1), -kPiD, kPiD);
}

// Azimuth of lobe p's exit relative to the incident azimuth.
double exitAzimuth(int p, double gammaO, double gammaT) { return 2 * p * gammaT - 2 * gammaO + p * kPiD; }

double Np(double dphi, int p, double s, double gammaO, double gammaT) {
    return trimmedLogistic(std::remainder(dphi - exitAzimuth(p, gammaO, gammaT), 2 * kPiD), s);
}

}  // namespace

struct HairBxDF::Lobes {
    double h, gammaO;  // the offset across the fibre, asin(h)
    double sinThetaO, cosThetaO, phiO, gammaT;
    // theta_o tilted by the scales for each lobe (lobe kPMax untilted).
    std::array<double, kPMax + 1> sinThetaP, cosThetaP;
    std::array<std::array<double, 4>, kPMax + 1> ap;
    std::array<double, kPMax + 1> apPdf;
    bool valid;  // some light is scattered
};

HairBxDF::HairBxDF(const HairParams& p) : BxDF(true) {
    h_ = clampd(p.h, -1, 1);
    eta_ = p.eta;
    fibre_ = p.fibre;
    for (int c = 0; c < 4; ++c) sigmaA_[c] = clampd(p.sigmaA[c], 0, 1e30);  // also maps NaN to 0
    meanChannels_ = p.spectral ? 4 : 3;
    const double bm = p.betaM, bn = p.betaN;
    v_[0] = std::pow(0.726 * bm + 0.812 * bm * bm + 3.7 * std::pow(bm, 20), 2);
    v_[1] = 0.25 * v_[0];
    v_[2] = 4 * v_[0];
    for (int i = 3; i <= kPMax; ++i) v_[i] = v_[2];
    s_ = std::sqrt(kPiD / 8) * (0.265 * bn + 1.194 * bn * bn + 5.372 * std::pow(bn, 22));
    // sin, cos of 2^k alpha by the double-angle formulas.
    sin2kAlpha_[0] = std::sin(double(p.alphaDegrees) * kPiD / 180);
    cos2kAlpha_[0] = safeSqrtD(1 - sin2kAlpha_[0] * sin2kAlpha_[0]);
    for (int i = 1; i < kPMax; ++i) {
        sin2kAlpha_[i] = 2 * cos2kAlpha_[i - 1] * sin2kAlpha_[i - 1];
        cos2kAlpha_[i] = cos2kAlpha_[i - 1] * cos2kAlpha_[i - 1] - sin2kAlpha_[i - 1] * sin2kAlpha_[i - 1];
    }
}

HairBxDF::Lobes HairBxDF::lobes(Vec3 wo, double h) const {
    Lobes L;
    L.h = h;
    L.gammaO = std::asin(h);
    L.sinThetaO = clampd(wo.x, -1, 1);
    L.cosThetaO = safeSqrtD(1 - L.sinThetaO * L.sinThetaO);
    L.phiO = std::atan2(double(wo.z), double(wo.y));

    // The refracted ray: theta_t by Snell's law, gamma_t by the modified index
    // eta' = sqrt(eta^2 - sin^2 theta_o) / cos theta_o of the fibre's cross-section.
    const double sinThetaT = L.sinThetaO / eta_, cosThetaT = safeSqrtD(1 - sinThetaT * sinThetaT);
    const double etaNum = safeSqrtD(eta_ * eta_ - L.sinThetaO * L.sinThetaO);
    double sinGammaT;  // h / eta', guarded where eta' is 0 or infinite
    if (etaNum > 0) sinGammaT = clampd(h * L.cosThetaO / etaNum, -1, 1);
    else sinGammaT = h == 0 || L.cosThetaO == 0 ? 0.0 : std::copysign(1.0, h);
    L.gammaT = std::asin(sinGammaT);
    const double cosGammaT = safeSqrtD(1 - sinGammaT * sinGammaT);
    // Length of one pass through the fibre (radius 1).
    const double pathLength = cosThetaT > 0 ? 2 * cosGammaT / cosThetaT : (cosGammaT > 0 ? INFINITY : 0.0);

    // Attenuation: Fresnel at the first intersection, then per pass absorption T and one
    // more Fresnel reflection per internal bounce; lobe kPMax sums the geometric series.
    const double fr = fresnelDielectric(float(L.cosThetaO * safeSqrtD(1 - h * h)), float(eta_));
    double sumAvg = 0;
    for (int c = 0; c < 4; ++c) {
        const double T = sigmaA_[c] == 0 ? 1.0 : std::exp(-sigmaA_[c] * pathLength);
        L.ap[0][c] = fr;
        L.ap[1][c] = (1 - fr) * (1 - fr) * T;
        for (int p = 2; p < kPMax; ++p) L.ap[p][c] = L.ap[p - 1][c] * T * fr;
        const double rest = 1 - T * fr;
        L.ap[kPMax][c] = rest > 0 ? L.ap[kPMax - 1][c] * fr * T / rest : 0.0;
    }
    for (int p = 0; p <= kPMax; ++p) {
        L.apPdf[p] = meanChannels_ == 4 ? (L.ap[p][0] + L.ap[p][1] + L.ap[p][2] + L.ap[p][3]) / 4
                                        : (L.ap[p][0] + L.ap[p][1] + L.ap[p][2]) / 3;
        sumAvg += L.apPdf[p];
    }
    L.valid = sumAvg > 0 && std::isfinite(sumAvg);
    for (double& a : L.apPdf) a = L.valid ? a / sumAvg : 0.0;

    // The scales tilt the lobes: R by -2 alpha, TT by alpha, TRT by 4 alpha.
    const double s = L.sinThetaO, co = L.cosThetaO;
    L.sinThetaP[0] = s * cos2kAlpha_[1] - co * sin2kAlpha_[1];
    L.cosThetaP[0] = co * cos2kAlpha_[1] + s * sin2kAlpha_[1];
    L.sinThetaP[1] = s * cos2kAlpha_[0] + co * sin2kAlpha_[0];
    L.cosThetaP[1] = co * cos2kAlpha_[0] - s * sin2kAlpha_[0];
    L.sinThetaP[2] = s * cos2kAlpha_[2] + co * sin2kAlpha_[2];
    L.cosThetaP[2] = co * cos2kAlpha_[2] - s * sin2kAlpha_[2];
    for (int p = kPMax; p <= kPMax; ++p) {
        L.sinThetaP[p] = s;
        L.cosThetaP[p] = co;
    }
    // A tilt past the pole reflects theta back into range.
    for (double& c : L.cosThetaP) c = std::fabs(c);
    return L;
}

Spectrum HairBxDF::radiance(const Lobes& L, Vec3 wi) const {
    const double sinThetaI = clampd(wi.x, -1, 1), cosThetaI = safeSqrtD(1 - sinThetaI * sinThetaI);
    const double dphi = std::atan2(double(wi.z), double(wi.y)) - L.phiO;
    std::array<double, 4> sum{0, 0, 0, 0};
    for (int p = 0; p <= kPMax; ++p) {
        const double n = p < kPMax ? Np(dphi, p, s_, L.gammaO, L.gammaT) : 1 / (2 * kPiD);
        const double m = Mp(cosThetaI, L.cosThetaP[p], sinThetaI, L.sinThetaP[p], v_[p]);
        for (int c = 0; c < 4; ++c) sum[c] += m * n * L.ap[p][c];
    }
    // The lobes give f |cos wi|.
    const double cosI = std::fabs(double(wi.z));
    Spectrum out;
    for (int c = 0; c < 4; ++c) out[c] = float(cosI > 0 ? sum[c] / cosI : sum[c]);  // all four: c3 is g in RGB mode
    return out;
}

double HairBxDF::density(const Lobes& L, double sinThetaI, double cosThetaI, double dphi) const {
    double pdf = 0;
    for (int p = 0; p <= kPMax; ++p) {
        if (L.apPdf[p] == 0) continue;
        const double n = p < kPMax ? Np(dphi, p, s_, L.gammaO, L.gammaT) : 1 / (2 * kPiD);
        pdf += Mp(cosThetaI, L.cosThetaP[p], sinThetaI, L.sinThetaP[p], v_[p]) * L.apPdf[p] * n;
    }
    return pdf;
}

// The adjoint at a vertex a light path found (wo towards the light, wi towards the camera;
// thesis sec. 5.2: f* |cos wi| must carry what the radiance form carries for the same path).
// The lobes are not reciprocal (the attenuation belongs to the exit direction), so the
// radiance form runs with the directions exchanged. On a ribbon facing
// each ray, that ribbon faced the light's ray: a light path meets the fibre over its width
// projected towards the light, P(wo) = sqrt(1 - sin^2 theta), where the camera sees it over
// P(wi), not over the ribbon's cosine |wi.z|.
Spectrum HairBxDF::adjoint(Vec3 wo, Vec3 wi) const {
    const Spectrum swapped = radiance(lobes(wi, h_), wo);
    if (fibre_ != FibreKind::FacingRay) return swapped;
    const double pO = safeSqrtD(1 - double(wo.x) * wo.x), pI = safeSqrtD(1 - double(wi.x) * wi.x);
    const double cosO = std::fabs(double(wo.z)), cosI = std::fabs(double(wi.z));
    if (!(pO > 0) || !(cosI > 0)) return {};
    // radiance() divides by |wo.z|: the lobes' sum is that times |wo.z|.
    return swapped * float(cosO * pI / (pO * cosI));
}

Spectrum HairBxDF::f(Vec3 wo, Vec3 wi, TransportMode mode) const {
    return mode == TransportMode::Importance ? adjoint(wo, wi) : radiance(lobes(wo, h_), wi);
}

float HairBxDF::pdf(Vec3 wo, Vec3 wi, TransportMode mode) const {
    const Lobes L = lobes(wo, h_);
    if (!L.valid) return 0;
    const double sinThetaI = clampd(wi.x, -1, 1), cosThetaI = safeSqrtD(1 - sinThetaI * sinThetaI);
    const double dphi = std::atan2(double(wi.z), double(wi.y)) - L.phiO;
    return float(density(L, sinThetaI, cosThetaI, mode == TransportMode::Radiance ? dphi : -dphi));
}

std::optional<BSDFSample> HairBxDF::sample(Vec3 wo, float ucIn, Vec2 u, TransportMode mode) const {
    const Lobes L = lobes(wo, h_);
    if (!L.valid) return std::nullopt;
    // The lobe by its share of the attenuation; uc rescaled to pick the azimuth within it.
    double uc = clampd(ucIn, 0, 1);
    int p = 0;
    double before = 0;
    while (p < kPMax && (uc >= before + L.apPdf[p] || L.apPdf[p] == 0)) before += L.apPdf[p++];
    uc = clampd((uc - before) / L.apPdf[p], 0, 1);

    // theta_i from Mp: a cosine on the cone around the tilted mirror direction, then its
    // projection onto the fibre axis. u0 is kept off 0 where e^{-2/v} underflows.
    const double v = v_[p];
    const double u0 = std::max(double(u.x), 1e-300);
    const double cosTheta = clampd(1 + v * std::log(u0 + (1 - u0) * std::exp(-2 / v)), -1, 1);
    const double sinTheta = safeSqrtD(1 - cosTheta * cosTheta);
    const double cosPhi = std::cos(2 * kPiD * u.y);
    const double sinThetaI = clampd(-cosTheta * L.sinThetaP[p] + sinTheta * cosPhi * L.cosThetaP[p], -1, 1);
    const double cosThetaI = safeSqrtD(1 - sinThetaI * sinThetaI);

    // The azimuth from Np (uniform for the last lobe).
    const double dphi = p < kPMax ? exitAzimuth(p, L.gammaO, L.gammaT) + sampleTrimmedLogistic(uc, s_) : 2 * kPiD * uc;
    // The adjoint's lobes lie at the mirrored azimuths (exit azimuths of -dphi).
    const double phiI = L.phiO + (mode == TransportMode::Radiance ? dphi : -dphi);
    const Vec3 wi(float(sinThetaI), float(cosThetaI * std::cos(phiI)), float(cosThetaI * std::sin(phiI)));

    const float pdf = float(density(L, sinThetaI, cosThetaI, dphi));
    if (!(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
    const Spectrum f = mode == TransportMode::Radiance ? radiance(L, wi) : adjoint(wo, wi);
    return BSDFSample{f, wi, pdf, uint8_t(kReflection | kGlossy), 1};
}

Spectrum HairBxDF::sigmaAFromConcentration(float eumelanin, float pheomelanin, const SampledWavelengths* lambda) {
    const Spectrum rgb = Spectrum(0.419f, 0.697f, 1.37f) * eumelanin + Spectrum(0.187f, 0.4f, 1.05f) * pheomelanin;
    return lambda ? liftUnbounded(rgb, *lambda) : rgb;
}

Spectrum HairBxDF::sigmaAFromReflectance(const Spectrum& c, float betaN) {
    const double b = betaN;
    const double d = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * b * b * b + 5.574 * b * b * b * b + 0.245 * std::pow(b, 5);
    Spectrum out;
    for (int i = 0; i < 4; ++i) {  // c3 is g in RGB mode, a wavelength's value in spectral
        const double l = std::log(double(c[i])) / d;  // c = 0: infinite absorption
        out[i] = float(std::min(l * l, 1e30));
    }
    return out;
}

}  // namespace ps
