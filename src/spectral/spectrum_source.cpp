#include "spectral/spectrum_source.h"
#include "spectral/illuminant_data.h"
#include "spectral/rgb_to_spectrum.h"

#include <algorithm>
#include <cmath>

namespace ps {

namespace {

template <class... F>
struct Overload : F... {
    using F::operator()...;
};
template <class... F>
Overload(F...) -> Overload<F...>;

}  // namespace

double planck(double lambdaNm, double kelvin) {
    if (!(kelvin > 0)) return 0;
    // CODATA 2010 constants, as pbrt-v4.
    const double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
    const double l = lambdaNm * 1e-9;
    return (2 * h * c * c) / (std::pow(l, 5) * (std::exp((h * c) / (l * kb * kelvin)) - 1));
}

SpectrumSource SpectrumSource::constant(float c) { return SpectrumSource(Constant{c}); }

SpectrumSource SpectrumSource::piecewiseLinear(std::vector<float> lambda, std::vector<float> value) {
    PiecewiseLinearTable t;
    t.lambda = std::move(lambda);
    t.value = std::move(value);
    return piecewiseLinear(std::move(t));
}

SpectrumSource SpectrumSource::piecewiseLinear(PiecewiseLinearTable table) {
    // Callers validate (pbrt-v4 rejects non-increasing wavelengths); a mismatched table is
    // cut to its pairs rather than read out of bounds.
    const size_t n = std::min(table.lambda.size(), table.value.size());
    table.lambda.resize(n);
    table.value.resize(n);
    return SpectrumSource(Tabulated{std::make_shared<const PiecewiseLinearTable>(std::move(table))});
}

SpectrumSource SpectrumSource::dense(std::shared_ptr<const DenseSpectrum> s) { return SpectrumSource(Dense{std::move(s)}); }

SpectrumSource SpectrumSource::blackbody(float kelvin) {
    const double peak = planck(2.8977721e-3 / kelvin * 1e9, kelvin);
    return SpectrumSource(Blackbody{kelvin, peak > 0 ? float(1 / peak) : 0.0f});
}

SpectrumSource SpectrumSource::rgbAlbedo(const RGBColorSpace& space, std::array<float, 3> rgb) {
    return SpectrumSource(RGBAlbedo{RGBToSpectrumTable::forSpace(space)(rgb)});
}

namespace {

// The scale and normalised RGB of the unbounded and illuminant forms.
std::pair<float, SigmoidPolynomial> halfBrightness(const RGBColorSpace& space, std::array<float, 3> rgb) {
    for (float& v : rgb) v = std::max(v, 0.0f);
    const float scale = 2 * std::max({rgb[0], rgb[1], rgb[2]});
    if (scale > 0)
        for (float& v : rgb) v /= scale;
    return {scale, RGBToSpectrumTable::forSpace(space)(scale > 0 ? rgb : std::array<float, 3>{0, 0, 0})};
}

}  // namespace

SpectrumSource SpectrumSource::rgbUnbounded(const RGBColorSpace& space, std::array<float, 3> rgb) {
    auto [scale, poly] = halfBrightness(space, rgb);
    return SpectrumSource(RGBUnbounded{scale, poly});
}

SpectrumSource SpectrumSource::rgbIlluminant(const RGBColorSpace& space, std::array<float, 3> rgb) {
    auto [scale, poly] = halfBrightness(space, rgb);
    return SpectrumSource(RGBIlluminant{scale, poly, &colorimetry(space).illuminant});
}

SpectrumSource::Kind SpectrumSource::kind() const { return Kind(v_.index()); }

float SpectrumSource::at(float lambda) const {
    return std::visit(Overload{
                          [](const Constant& s) { return s.c; },
                          [&](const Tabulated& s) { return s.table->at(lambda); },
                          [&](const Dense& s) { return s.s->at(lambda); },
                          [&](const Blackbody& s) { return float(planck(lambda, s.kelvin) * s.normalization); },
                          [&](const RGBAlbedo& s) { return s.poly(lambda); },
                          [&](const RGBUnbounded& s) { return s.scale * s.poly(lambda); },
                          [&](const RGBIlluminant& s) { return s.scale * s.poly(lambda) * s.illuminant->at(lambda); },
                      },
                      v_);
}

namespace {

// The sigmoid polynomial at the four wavelengths: a grey (infinite constant term) once, else
// without branches so that the four run as one vector operation. Inlined into sample(): as a
// call, its result went back through memory and cost the spectral path tracer 4%.
[[gnu::always_inline]] inline void polynomial(const SigmoidPolynomial& p, const SampledWavelengths& w, SpectralValues& out) {
    if (!std::isfinite(p.c2) || (p.c0 == 0 && p.c1 == 0)) {
        out.fill(p(0));
        return;
    }
    for (int i = 0; i < kWavelengthSamples; ++i) {
        const float l = w.lambda[size_t(i)], x = (p.c0 * l + p.c1) * l + p.c2;
        out[size_t(i)] = 0.5f + x / (2 * std::sqrt(1 + x * x));
    }
}

}  // namespace

SpectralValues SpectrumSource::sample(const SampledWavelengths& w) const {
    // One dispatch for the four wavelengths (this runs at every hit in spectral mode).
    SpectralValues out;
    auto each = [&](auto f) {
        for (int i = 0; i < kWavelengthSamples; ++i) out[size_t(i)] = f(w.lambda[size_t(i)]);
    };
    std::visit(Overload{
                   [&](const Constant& s) { out.fill(s.c); },
                   [&](const Tabulated& s) { each([&](float l) { return s.table->at(l); }); },
                   [&](const Dense& s) { each([&](float l) { return s.s->at(l); }); },
                   [&](const Blackbody& s) { each([&](float l) { return float(planck(l, s.kelvin) * s.normalization); }); },
                   [&](const RGBAlbedo& s) { polynomial(s.poly, w, out); },
                   [&](const RGBUnbounded& s) {
                       polynomial(s.poly, w, out);
                       for (float& v : out) v *= s.scale;
                   },
                   [&](const RGBIlluminant& s) {
                       polynomial(s.poly, w, out);
                       for (int i = 0; i < kWavelengthSamples; ++i)
                           out[size_t(i)] *= s.scale * s.illuminant->at(w.lambda[size_t(i)]);
                   },
               },
               v_);
    return out;
}

float SpectrumSource::maxValue() const {
    return std::visit(Overload{
                          [](const Constant& s) { return s.c; },
                          [](const Tabulated& s) { return s.table->maxValue(); },
                          [](const Dense& s) { return s.s->maxValue(); },
                          [](const Blackbody&) { return 1.0f; },
                          [](const RGBAlbedo& s) { return s.poly.maxValue(); },
                          [](const RGBUnbounded& s) { return s.scale * s.poly.maxValue(); },
                          [](const RGBIlluminant& s) { return s.scale * s.poly.maxValue() * s.illuminant->maxValue(); },
                      },
                      v_);
}

double innerProduct(const SpectrumSource& s, const float* table1nm) {
    double sum = 0;
    for (int i = 0; i < kCieSamples; ++i) sum += double(table1nm[i]) * s.at(float(kCieLambdaMin + i));
    return sum;
}

double SpectrumSource::photometric() const {
    if (const auto* s = std::get_if<RGBIlluminant>(&v_)) {
        double sum = 0;
        for (int i = 0; i < kCieSamples; ++i) sum += double(kCieY[i]) * s->illuminant->value[size_t(i)];
        return sum;
    }
    return innerProduct(*this, kCieY);
}

XYZ spectrumToXYZ(const SpectrumSource& s) {
    return {innerProduct(s, kCieX) / kCieYIntegral, innerProduct(s, kCieY) / kCieYIntegral,
            innerProduct(s, kCieZ) / kCieYIntegral};
}

DenseSpectrum daylightSpectrum(float kelvin) {
    DenseSpectrum out;
    const double cct = double(kelvin) * 1.4388 / 1.4380;
    if (cct < 4000) {
        const SpectrumSource bb = SpectrumSource::blackbody(float(cct));
        for (int i = 0; i < kCieSamples; ++i) out.value[size_t(i)] = bb.at(float(kCieLambdaMin + i));
        return out;
    }
    // Chromaticity of the daylight locus (CIE 015:2004 eq. 3.3, 3.4), then the weights of
    // the basis functions S1, S2 (eq. 3.5).
    const double t = cct, t2 = t * t, t3 = t2 * t;
    const double x = cct <= 7000 ? -4.6070e9 / t3 + 2.9678e6 / t2 + 0.09911e3 / t + 0.244063
                                 : -2.0064e9 / t3 + 1.9018e6 / t2 + 0.24748e3 / t + 0.237040;
    const double y = -3.0 * x * x + 2.870 * x - 0.275;
    const double m = 0.0241 + 0.2562 * x - 0.7341 * y;
    const double m1 = (-1.3515 - 1.7703 * x + 5.9114 * y) / m, m2 = (0.0300 - 31.4424 * x + 30.0717 * y) / m;
    PiecewiseLinearTable table;
    for (int i = 0; i < kDSeriesSamples; ++i) {
        table.lambda.push_back(kDSeriesLambda[i]);
        table.value.push_back(float((kDSeriesS0[i] + kDSeriesS1[i] * m1 + kDSeriesS2[i] * m2) * 0.01));
    }
    for (int i = 0; i < kCieSamples; ++i) out.value[size_t(i)] = table.at(float(kCieLambdaMin + i));
    return out;
}

}  // namespace ps
