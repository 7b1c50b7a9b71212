// A light's emitted spectrum in both colour modes (math/spectrum.h): the RGB the RGB mode
// emits, and for spectral mode the scene's spectrum divided by its photometric integral, as
// pbrt-v4's lights divide their `scale` (an RGB illuminant counts its colour space's
// illuminant alone, so its RGB magnitude survives; any other spectrum emits luminance 1).
// Multiplying by a factor (scale, power, illuminance) multiplies both.
#pragma once
#include "math/spectrum.h"
#include "spectral/sampled_spectrum.h"

namespace ps {

class LightSpectrum {
public:
    LightSpectrum() : LightSpectrum(Spectrum(1.0f), SpectrumSource::rgbIlluminant(srgbColorSpace(), {1, 1, 1})) {}
    LightSpectrum(Spectrum rgb, SpectrumSource spectrum) : rgb_(rgb), spectrum_(std::move(spectrum)) {
        const double phi = spectrum_.photometric();
        scale_ = phi > 0 ? float(1 / phi) : 0.0f;
    }
    // The RGB value in RGB mode (lambda null), the values at lambda in spectral mode.
    Spectrum operator()(const SampledWavelengths* lambda) const {
        return lambda ? sampleSpectrum(spectrum_, *lambda) * scale_ : rgb_;
    }
    const Spectrum& rgb() const { return rgb_; }
    // The spectral values' maximum over wavelengths, in units where the colour space's white
    // of RGB (1, 1, 1) is 1. The light BVH weighs emitters by it, as pbrt-v4 by MaxValue: a
    // saturated light's luminance understates its strongest wavelengths, and the estimates
    // there (and the channel they land in) then get too few samples (fireflies).
    float maxValue() const {
        static const float white = [] {
            const SpectrumSource w = SpectrumSource::rgbIlluminant(srgbColorSpace(), {1, 1, 1});
            return float(w.maxValue() / w.photometric());
        }();
        return spectrum_.maxValue() * scale_ / white;
    }
    LightSpectrum operator*(float s) const {
        LightSpectrum r = *this;
        r.rgb_ *= s;
        r.scale_ *= s;
        return r;
    }

private:
    Spectrum rgb_;
    SpectrumSource spectrum_;
    float scale_ = 1;
};

}  // namespace ps
