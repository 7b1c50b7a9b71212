#include "spectral/sampled_spectrum.h"

#include <algorithm>

#include "spectral/cie.h"
#include "spectral/rgb_to_spectrum.h"

namespace ps {

namespace {

Spectrum sampleOf(const SpectralValues& v) { return Spectrum::sampled(v[0], v[1], v[2], v[3]); }

// pbrt-v4's unbounded form: scale S(rgb / scale) with scale = 2 max(rgb).
Spectrum halfBrightnessLift(const Spectrum& rgb, const SampledWavelengths& w, const RGBColorSpace& space) {
    const float r = std::max(rgb.r, 0.0f), g = std::max(rgb.g, 0.0f), b = std::max(rgb.b, 0.0f);
    const float scale = 2 * std::max({r, g, b});
    if (!(scale > 0)) return {};
    const SigmoidPolynomial poly = RGBToSpectrumTable::forSpace(space)({r / scale, g / scale, b / scale});
    return Spectrum::sampled(poly(w.lambda[0]), poly(w.lambda[1]), poly(w.lambda[2]), poly(w.lambda[3])) * scale;
}

}  // namespace

Spectrum sampleSpectrum(const SpectrumSource& s, const SampledWavelengths& w) { return sampleOf(s.sample(w)); }

Spectrum liftAlbedo(const Spectrum& rgb, const SampledWavelengths& w, const RGBColorSpace& space) {
    const SigmoidPolynomial poly = RGBToSpectrumTable::forSpace(space)(
        {std::clamp(rgb.r, 0.0f, 1.0f), std::clamp(rgb.g, 0.0f, 1.0f), std::clamp(rgb.b, 0.0f, 1.0f)});
    return Spectrum::sampled(poly(w.lambda[0]), poly(w.lambda[1]), poly(w.lambda[2]), poly(w.lambda[3]));
}

Spectrum liftUnbounded(const Spectrum& rgb, const SampledWavelengths& w, const RGBColorSpace& space) {
    return halfBrightnessLift(rgb, w, space);
}

Spectrum liftIlluminant(const Spectrum& rgb, const SampledWavelengths& w, const RGBColorSpace& space) {
    const DenseSpectrum& illum = colorimetry(space).illuminant;  // sum ybar * illum = kCieYIntegral
    Spectrum s = halfBrightnessLift(rgb, w, space);
    for (int i = 0; i < kWavelengthSamples; ++i) s[i] *= illum.at(w.lambda[size_t(i)]) / kCieYIntegral;
    return s;
}

}  // namespace ps
