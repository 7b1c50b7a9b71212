#include "scene/spectra.h"
#include "util/input_files.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

namespace ps {

namespace {

// Everything is integrated on a 1 nm grid over the visible range of the CIE tables.
constexpr int kGridMin = 360, kGridMax = 830, kSamples = kGridMax - kGridMin + 1;

// CIE 1931 colour matching functions: the multi-lobe Gaussian fit of Wyman, Sloan and
// Shirley 2013 ("Simple analytic approximations to the CIE XYZ color matching functions").
// Its small errors cancel to first order because every result is white-balanced against
// D65 computed with the same fit.
double lobe(double l, double mu, double s1, double s2) {
    double t = (l - mu) / (l < mu ? s1 : s2);
    return std::exp(-0.5 * t * t);
}
double cieX(double l) { return 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) - 0.065 * lobe(l, 501.1, 20.4, 26.2); }
double cieY(double l) { return 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1); }
double cieZ(double l) { return 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8); }

// CIE standard illuminant D65, relative spectral power at 10 nm from 380 to 780 nm
// (held constant beyond the ends, where the matching functions are negligible).
const double kD65[41] = {49.9755, 54.6482, 82.7549, 91.486,  93.4318, 86.6823, 104.865, 117.008, 117.812,
                         114.861, 115.923, 108.811, 109.354, 107.802, 104.79,  107.689, 104.405, 104.046,
                         100.0,   96.3342, 95.788,  88.6856, 90.0062, 89.5991, 87.6987, 83.2886, 83.6992,
                         80.0268, 80.2146, 82.2778, 78.2842, 69.7213, 71.6091, 74.349,  61.604,  69.8856,
                         75.087,  63.5927, 46.4182, 66.8054, 63.3828};
double d65(double l) {
    double x = (l - 380) / 10;
    if (x <= 0) return kD65[0];
    if (x >= 40) return kD65[40];
    int i = int(x);
    return kD65[i] + (x - i) * (kD65[i + 1] - kD65[i]);
}

// XYZ -> linear sRGB (IEC 61966-2-1, D65 white).
const double kXYZToRGB[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                {-0.9692660, 1.8760108, 0.0415560},
                                {0.0556434, -0.2040259, 1.0572252}};

void toRGB(const double xyz[3], double rgb[3]) {
    for (int c = 0; c < 3; ++c) rgb[c] = kXYZToRGB[c][0] * xyz[0] + kXYZToRGB[c][1] * xyz[1] + kXYZToRGB[c][2] * xyz[2];
}

// Tabulated once: matching functions, D65, the R/G/B band weights and the RGB of D65 at Y = 1.
struct Tables {
    double cmf[kSamples][3];
    double illum[kSamples];   // D65
    double band[kSamples][3]; // max(0, sRGB matching function), per channel
    double bandSum[3] = {0, 0, 0};
    double yD65 = 0;          // integral of D65 * ybar
    double white[3];          // linear sRGB of D65 scaled to Y = 1 (close to 1 each)
    Tables() {
        double xyzW[3] = {0, 0, 0};
        for (int i = 0; i < kSamples; ++i) {
            double l = kGridMin + i;
            cmf[i][0] = cieX(l);
            cmf[i][1] = cieY(l);
            cmf[i][2] = cieZ(l);
            illum[i] = d65(l);
            double rgb[3];
            toRGB(cmf[i], rgb);
            for (int c = 0; c < 3; ++c) {
                band[i][c] = std::max(0.0, rgb[c]);
                bandSum[c] += band[i][c];
                xyzW[c] += illum[i] * cmf[i][c];
            }
        }
        yD65 = xyzW[1];
        for (double& v : xyzW) v /= yD65;
        toRGB(xyzW, white);
    }
};

const Tables& tables() {
    static const Tables t;
    return t;
}

// Samples a function of wavelength onto the 1 nm grid.
template <typename F>
void sampleGrid(F&& f, double out[kSamples]) {
    for (int i = 0; i < kSamples; ++i) out[i] = f(double(kGridMin + i));
}

Spectrum convert(const double s[kSamples], SpectrumKind kind) {
    const Tables& t = tables();
    if (kind == SpectrumKind::Unbounded) {
        double acc[3] = {0, 0, 0};
        for (int i = 0; i < kSamples; ++i)
            for (int c = 0; c < 3; ++c) acc[c] += s[i] * t.band[i][c];
        return {float(acc[0] / t.bandSum[0]), float(acc[1] / t.bandSum[1]), float(acc[2] / t.bandSum[2])};
    }
    const bool albedo = kind == SpectrumKind::Albedo;
    double xyz[3] = {0, 0, 0};
    for (int i = 0; i < kSamples; ++i) {
        double v = albedo ? std::clamp(s[i], 0.0, 1.0) * t.illum[i] : s[i];
        for (int c = 0; c < 3; ++c) xyz[c] += v * t.cmf[i][c];
    }
    // Albedo: relative to a perfect white under D65. Illuminant: chromaticity at Y = 1.
    double norm = albedo ? t.yD65 : xyz[1];
    if (!(norm > 0)) return Spectrum(0.0f);
    for (double& v : xyz) v /= norm;
    double rgb[3];
    toRGB(xyz, rgb);
    auto channel = [&](int c) { return float(std::max(0.0, rgb[c] / t.white[c])); };  // out-of-gamut parts clip
    const Spectrum out(channel(0), channel(1), channel(2));
    return albedo ? clamp(out, 0, 1) : out;
}

}  // namespace

Spectrum xyzToLinearSRGB(double X, double Y, double Z) {
    double xyz[3] = {X, Y, Z}, rgb[3];
    toRGB(xyz, rgb);
    return {float(rgb[0]), float(rgb[1]), float(rgb[2])};
}

Spectrum chromaticityToRGB(double x, double y) {
    if (!(y > 0)) return Spectrum(0.0f);
    auto rgbOf = [](double cx, double cy) {
        double xyz[3] = {cx / cy, 1.0, (1 - cx - cy) / cy}, rgb[3];
        toRGB(xyz, rgb);
        return std::array<double, 3>{rgb[0], rgb[1], rgb[2]};
    };
    auto c = rgbOf(x, y), w = rgbOf(0.31271, 0.32902);  // D65
    return {float(std::max(0.0, c[0] / w[0])), float(std::max(0.0, c[1] / w[1])), float(std::max(0.0, c[2] / w[2]))};
}

bool sampledSpectrumIsConstant(const std::vector<float>& lambda, const std::vector<float>& value) {
    if (lambda.empty() || lambda.size() != value.size() || lambda.front() > kGridMin || lambda.back() < kGridMax) return false;
    return std::all_of(value.begin(), value.end(), [&](float v) { return v == value[0]; });
}

Spectrum sampledSpectrumToRGB(const std::vector<float>& lambda, const std::vector<float>& value, SpectrumKind kind) {
    double s[kSamples] = {};
    const size_t n = std::min(lambda.size(), value.size());
    if (n == 0) return Spectrum(0.0f);
    size_t j = 0;  // lambda[j] <= l < lambda[j+1]; the grid ascends, so j only moves forward
    for (int i = 0; i < kSamples; ++i) {
        double l = kGridMin + i;
        if (l < lambda[0] || l > lambda[n - 1]) continue;
        while (j + 1 < n && lambda[j + 1] <= l) ++j;
        if (j + 1 >= n) {
            s[i] = value[n - 1];
            continue;
        }
        double t = (l - lambda[j]) / (double(lambda[j + 1]) - lambda[j]);
        s[i] = value[j] + t * (double(value[j + 1]) - value[j]);
    }
    return convert(s, kind);
}

std::vector<Spectrum> reflectanceSampleWeights(const std::vector<float>& lambda) {
    const Tables& t = tables();
    const size_t n = lambda.size();
    std::vector<Spectrum> w(n);
    for (size_t k = 0; k < n; ++k) {
        // The hat function of sample k (1 at lambda[k], 0 at its neighbours), extended flat
        // beyond the first and last sample.
        auto hat = [&](double l) {
            if (l <= lambda[k]) {
                if (k == 0) return 1.0;
                return l <= lambda[k - 1] ? 0.0 : (l - lambda[k - 1]) / (double(lambda[k]) - lambda[k - 1]);
            }
            if (k + 1 == n) return 1.0;
            return l >= lambda[k + 1] ? 0.0 : (double(lambda[k + 1]) - l) / (double(lambda[k + 1]) - lambda[k]);
        };
        double xyz[3] = {0, 0, 0}, rgb[3];
        for (int i = 0; i < kSamples; ++i) {
            double v = hat(double(kGridMin + i)) * t.illum[i] / t.yD65;
            for (int c = 0; c < 3; ++c) xyz[c] += v * t.cmf[i][c];
        }
        toRGB(xyz, rgb);
        for (int c = 0; c < 3; ++c) w[k][c] = float(rgb[c] / t.white[c]);
    }
    return w;
}

Spectrum blackbodyToRGB(float kelvin) { return blackbodyToRGB(kelvin, SpectrumKind::Illuminant); }

Spectrum blackbodyToRGB(float kelvin, SpectrumKind kind) {
    if (!(kelvin > 0)) return Spectrum(0.0f);
    // pbrt normalises its blackbody to 1 at the peak (Wien's displacement law).
    double peak = planck(2.8977721e-3 / kelvin * 1e9, kelvin);
    double s[kSamples];
    sampleGrid([&](double l) { return planck(l, kelvin) / peak; }, s);
    return convert(s, kind);
}

std::string readSpectrumFile(const std::string& path, std::vector<float>& lambda, std::vector<float>& value) {
    lambda.clear();
    value.clear();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return "\"" + path + "\" is not a readable file";
    noteInputFile(path);
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return "cannot open \"" + path + "\"";
    std::string text;
    char buf[1 << 14];
    size_t got;
    while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, got);
    std::fclose(f);

    std::vector<double> numbers;
    const char* p = text.data();
    const char* end = p + text.size();
    while (p < end) {
        char c = *p;
        if (c == '#') {
            while (p < end && *p != '\n') ++p;
        } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',') {
            ++p;
        } else {
            const char* q = p;
            while (q < end && !(*q == ' ' || *q == '\t' || *q == '\n' || *q == '\r' || *q == ',' || *q == '#')) ++q;
            double v = 0;
            const char* b = (*p == '+') ? p + 1 : p;
            auto [ptr, ec] = std::from_chars(b, q, v);
            if (ec != std::errc() || ptr != q || !std::isfinite(v))
                return "\"" + path + "\": \"" + std::string(p, std::min<size_t>(q - p, 40)) + "\" is not a number";
            numbers.push_back(v);
            p = q;
        }
    }
    if (numbers.empty()) return "\"" + path + "\" holds no wavelength/value pairs";
    if (numbers.size() % 2 != 0) return "\"" + path + "\" holds an odd number of values (expected wavelength/value pairs)";
    for (size_t i = 0; i < numbers.size(); i += 2) {
        if (!lambda.empty() && numbers[i] <= lambda.back()) return "\"" + path + "\": wavelengths must increase";
        lambda.push_back(float(numbers[i]));
        value.push_back(float(numbers[i + 1]));
    }
    return "";
}

// ---- pbrt-v4's named spectra (PBRT-CONVENTIONS §8 `spectrum`), reduced to what an RGB
// renderer needs. pbrt stores these as measured curves; here each is a value per channel.
namespace {

struct Metal {
    Spectrum eta, k;
};

// Complex refractive indices per channel. Ag, Al, Au and Cu are the widely used RGB values
// of the measured curves (they reproduce the normal-incidence reflectance of the spectral
// Fresnel curve under D65 to about 2%, better than band averages of eta and k do). CuZn is
// pbrt's curve at 650/550/450 nm; MgO and TiO2 (dielectrics, k ~ 0) are band averages of
// pbrt's curves as sampledSpectrumToRGB(..., Unbounded) computes them.
const std::map<std::string, Metal>& metals() {
    static const std::map<std::string, Metal> m = {
        {"Ag", {{0.155265f, 0.116723f, 0.138342f}, {4.82835f, 3.12225f, 2.14696f}}},
        {"Al", {{1.65746f, 0.880369f, 0.521229f}, {9.22387f, 6.26952f, 4.837f}}},
        {"Au", {{0.143119f, 0.374957f, 1.44248f}, {3.98316f, 2.38572f, 1.60322f}}},
        {"Cu", {{0.200438f, 0.924033f, 1.10221f}, {3.91295f, 2.45285f, 2.14219f}}},
        {"CuZn", {{0.444f, 0.527f, 1.094f}, {3.695f, 2.765f, 1.829f}}},
        {"MgO", {{1.7369f, 1.7415f, 1.7524f}, {0.0f, 0.0f, 0.0f}}},
        {"TiO2", {{2.9069f, 2.9693f, 3.1662f}, {0.0001f, 0.0f, 0.0006f}}},
    };
    return m;
}

// Index of refraction at the d line (587.6 nm) of pbrt's Sellmeier curves; dispersion is
// not modelled. pbrt's "glass-F5/F10/F11" are Schott SF5/SF10/SF11.
const std::map<std::string, float>& glasses() {
    static const std::map<std::string, float> g = {
        {"glass-BK7", 1.5168f}, {"glass-BAF10", 1.6700f}, {"glass-FK51A", 1.4866f}, {"glass-LASF9", 1.8503f},
        {"glass-F5", 1.6727f},  {"glass-F10", 1.7283f},   {"glass-F11", 1.7847f},
    };
    return g;
}

// CIE 1931 chromaticities (x, y) of pbrt's illuminant curves. Emission is normalised to
// luminance 1 anyway (§3), so the chromaticity is all that matters. Note that pbrt's
// "stdillum-D50" curve is bluer than CIE D50 (0.3457, 0.3585); we follow pbrt.
const std::map<std::string, std::pair<double, double>>& illuminants() {
    static const std::map<std::string, std::pair<double, double>> i = {
        {"stdillum-A", {0.44756, 0.40743}},   {"stdillum-D50", {0.33681, 0.35798}},
        {"stdillum-D65", {0.31271, 0.32902}}, {"illum-acesD60", {0.32168, 0.33767}},
        {"stdillum-F1", {0.31310, 0.33727}},  {"stdillum-F2", {0.37208, 0.37529}},
        {"stdillum-F3", {0.40910, 0.39430}},  {"stdillum-F4", {0.44018, 0.40329}},
        {"stdillum-F5", {0.31379, 0.34531}},  {"stdillum-F6", {0.37790, 0.38835}},
        {"stdillum-F7", {0.31292, 0.32933}},  {"stdillum-F8", {0.34588, 0.35875}},
        {"stdillum-F9", {0.37417, 0.37281}},  {"stdillum-F10", {0.34609, 0.35896}},
        {"stdillum-F11", {0.38052, 0.37713}}, {"stdillum-F12", {0.43695, 0.40441}},
    };
    return i;
}

}  // namespace

std::optional<Spectrum> namedSpectrumToRGB(const std::string& name, SpectrumKind kind) {
    if (name.rfind("metal-", 0) == 0) {
        size_t dash = name.rfind('-');
        std::string metal = name.substr(6, dash - 6), part = name.substr(dash + 1);
        auto it = metals().find(metal);
        if (dash <= 6 || it == metals().end() || (part != "eta" && part != "k")) return std::nullopt;
        Spectrum s = part == "eta" ? it->second.eta : it->second.k;
        return kind == SpectrumKind::Albedo ? clamp(s, 0, 1) : s;
    }
    if (auto it = glasses().find(name); it != glasses().end())
        return kind == SpectrumKind::Albedo ? Spectrum(1.0f) : Spectrum(it->second);
    if (auto it = illuminants().find(name); it != illuminants().end()) {
        Spectrum s = chromaticityToRGB(it->second.first, it->second.second);
        return kind == SpectrumKind::Albedo ? clamp(s, 0, 1) : s;
    }
    return std::nullopt;
}

}  // namespace ps
