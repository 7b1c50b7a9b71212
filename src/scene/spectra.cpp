#include "scene/spectra.h"

#include <cmath>
#include <map>

namespace ps {

namespace {

// CIE 1931 colour matching functions, multi-lobe Gaussian fit of Wyman, Sloan and
// Shirley 2013 ("Simple analytic approximations to the CIE XYZ colour matching functions").
float lobe(float l, float mu, float s1, float s2) {
    float t = (l - mu) / (l < mu ? s1 : s2);
    return std::exp(-0.5f * t * t);
}
float cieX(float l) { return 1.056f * lobe(l, 599.8f, 37.9f, 31.0f) + 0.362f * lobe(l, 442.0f, 16.0f, 26.7f) - 0.065f * lobe(l, 501.1f, 20.4f, 26.2f); }
float cieY(float l) { return 0.821f * lobe(l, 568.8f, 46.9f, 40.5f) + 0.286f * lobe(l, 530.9f, 16.3f, 31.1f); }
float cieZ(float l) { return 1.217f * lobe(l, 437.0f, 11.8f, 36.0f) + 0.681f * lobe(l, 459.0f, 26.0f, 13.8f); }

// CIE standard illuminant D65, relative spectral power at 10 nm from 380 to 780 nm.
const float kD65[41] = {49.9755f, 54.6482f, 82.7549f, 91.486f,  93.4318f, 86.6823f, 104.865f, 117.008f, 117.812f,
                        114.861f, 115.923f, 108.811f, 109.354f, 107.802f, 104.79f,  107.689f, 104.405f, 104.046f,
                        100.0f,   96.3342f, 95.788f,  88.6856f, 90.0062f, 89.5991f, 87.6987f, 83.2886f, 83.6992f,
                        80.0268f, 80.2146f, 82.2778f, 78.2842f, 69.7213f, 71.6091f, 74.349f,  61.604f,  69.8856f,
                        75.087f,  63.5927f, 46.4182f, 66.8054f, 63.3828f};
float d65(float l) {
    float x = (l - 380) / 10;
    if (x <= 0) return kD65[0];
    if (x >= 40) return kD65[40];
    int i = int(x);
    return lerp(x - i, kD65[i], kD65[i + 1]);
}

Spectrum xyzToLinearSRGB(double X, double Y, double Z) {
    return {float(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z), float(-0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z),
            float(0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z)};
}

template <typename F>
void integrateXYZ(F&& s, double& X, double& Y, double& Z) {
    X = Y = Z = 0;
    for (float l = 360; l <= 830; l += 1) {
        double v = s(l);
        X += v * cieX(l);
        Y += v * cieY(l);
        Z += v * cieZ(l);
    }
}

// Reflectances under D65, relative to a perfect white.
template <typename F>
Spectrum reflectanceToRGB(F&& s) {
    double X, Y, Z, Xw, Yw, Zw;
    integrateXYZ([&](float l) { return s(l) * d65(l); }, X, Y, Z);
    integrateXYZ([&](float l) { return d65(l); }, Xw, Yw, Zw);
    Spectrum rgb = xyzToLinearSRGB(X / Yw, Y / Yw, Z / Yw), white = xyzToLinearSRGB(Xw / Yw, 1, Zw / Yw);
    return rgb / white;
}

// Emission normalised to luminance 1, white-balanced so that D65 maps to (1,1,1).
template <typename F>
Spectrum illuminantToRGB(F&& s) {
    double X, Y, Z, Xw, Yw, Zw;
    integrateXYZ(s, X, Y, Z);
    integrateXYZ([&](float l) { return d65(l); }, Xw, Yw, Zw);
    if (!(Y > 0)) return Spectrum();
    Spectrum rgb = xyzToLinearSRGB(X / Y, 1, Z / Y), white = xyzToLinearSRGB(Xw / Yw, 1, Zw / Yw);
    return rgb / white;
}

double planck(double lambdaNm, double T) {
    const double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
    double l = lambdaNm * 1e-9;
    return (2 * h * c * c) / (std::pow(l, 5) * (std::exp((h * c) / (l * kb * T)) - 1));
}

}  // namespace

Spectrum sampledSpectrumToRGB(const std::vector<float>& lambda, const std::vector<float>& value, SpectrumKind kind) {
    auto s = [&](float l) -> double {
        if (lambda.empty() || l < lambda.front() || l > lambda.back()) return 0;
        size_t i = 1;
        while (i < lambda.size() && lambda[i] < l) ++i;
        if (i >= lambda.size()) return value.back();
        float span = lambda[i] - lambda[i - 1];
        float t = span > 0 ? (l - lambda[i - 1]) / span : 0;
        return lerp(t, value[i - 1], value[i]);
    };
    if (kind == SpectrumKind::Illuminant) return illuminantToRGB(s);
    return reflectanceToRGB(s);
}

Spectrum blackbodyToRGB(float kelvin) {
    return illuminantToRGB([&](float l) { return planck(l, kelvin); });
}

std::optional<Spectrum> namedSpectrumToRGB(const std::string& name, SpectrumKind kind) {
    // Metals: RGB values of the measured complex indices (eta, k) per channel.
    static const std::map<std::string, Spectrum> kMetals = {
        {"metal-Ag-eta", {0.155265f, 0.116723f, 0.138342f}},  {"metal-Ag-k", {4.82835f, 3.12225f, 2.14696f}},
        {"metal-Al-eta", {1.65746f, 0.880369f, 0.521229f}},   {"metal-Al-k", {9.22387f, 6.26952f, 4.837f}},
        {"metal-Au-eta", {0.143119f, 0.374957f, 1.44248f}},   {"metal-Au-k", {3.98316f, 2.38572f, 1.60322f}},
        {"metal-Cu-eta", {0.200438f, 0.924033f, 1.10221f}},   {"metal-Cu-k", {3.91295f, 2.45285f, 2.14219f}},
        {"metal-CuZn-eta", {0.444f, 0.527f, 1.094f}},         {"metal-CuZn-k", {3.695f, 2.765f, 1.829f}},
        {"metal-MgO-eta", {1.7318f, 1.7378f, 1.7506f}},       {"metal-MgO-k", {0.0f, 0.0f, 0.0f}},
        {"metal-TiO2-eta", {2.8717f, 2.9892f, 3.2237f}},      {"metal-TiO2-k", {0.0f, 0.0f, 0.0f}},
    };
    // Glasses: index at the d line (587.6 nm); dispersion is not modelled.
    static const std::map<std::string, float> kGlasses = {
        {"glass-BK7", 1.5168f}, {"glass-BAF10", 1.6700f}, {"glass-FK51A", 1.4866f}, {"glass-LASF9", 1.8503f},
        {"glass-F5", 1.6034f},  {"glass-F10", 1.6200f},   {"glass-F11", 1.6210f},
    };
    if (auto it = kMetals.find(name); it != kMetals.end()) return it->second;
    if (auto it = kGlasses.find(name); it != kGlasses.end()) return Spectrum(it->second);
    if (name == "stdillum-D65" || name == "illum-acesD60") return Spectrum(1.0f);
    if (name == "stdillum-A") return blackbodyToRGB(2856);
    if (name == "stdillum-D50") return blackbodyToRGB(5003);
    if (name.rfind("stdillum-F", 0) == 0) {
        warning("spectrum \"" + name + "\": fluorescent illuminants are approximated by D65");
        return Spectrum(1.0f);
    }
    (void)kind;
    return std::nullopt;
}

}  // namespace ps
