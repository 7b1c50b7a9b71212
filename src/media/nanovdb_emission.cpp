// The "nanovdb" medium's emission from its temperature grid (nanovdb_medium.h), with the
// semantics of pbrt-v4's NanoVDBMedium::Le.
#include <algorithm>
#include <cmath>

#include "media/nanovdb_medium.h"
#include "scene/spectra.h"
#include "spectral/sampled_spectrum.h"

namespace ps {

namespace {

// pbrt-v4 leaves temperatures at or below 100 K dark (their blackbody is all infrared).
constexpr float kColdest = 100;
constexpr int kTableSize = 4096;

// The blackbody of peak 1 as the film sees it in RGB mode: its chromaticity (luminance 1)
// times its luminance, the photometric integral the spectral film would measure.
Spectrum blackbodyRGB(float kelvin) {
    return blackbodyToRGB(kelvin, SpectrumKind::Illuminant) * float(SpectrumSource::blackbody(kelvin).photometric());
}

}  // namespace

float NanoVDBMedium::kelvin(Vec3 pMedium) const {
    if (!temperature_) return 0;
    const NanoVDBTemperature& t = *temperature_;
    return (t.grid.sample(t.grid.worldToIndex(pMedium)) - t.offset) * t.scale;
}

void NanoVDBMedium::buildBlackbodyTable() {
    if (!emissive() || !(temperature_->scale >= 0)) return;
    // With a scale of at least 0 the hottest point is the grid's largest value's.
    tableMax_ = (temperature_->grid.maxValue() - temperature_->offset) * temperature_->scale;
    if (!(tableMax_ > kColdest) || !std::isfinite(tableMax_)) return;
    rgbTable_.resize(kTableSize);
    for (int i = 0; i < kTableSize; ++i)
        rgbTable_[size_t(i)] = blackbodyRGB(kColdest + (tableMax_ - kColdest) * float(i) / float(kTableSize - 1));
}

Spectrum NanoVDBMedium::emission(Vec3 pMedium, const SampledWavelengths* lambda) const {
    const float T = kelvin(pMedium);
    if (!(T > kColdest)) return {};
    const float LeScale = temperature_->LeScale;
    if (lambda) return sampleSpectrum(SpectrumSource::blackbody(T), *lambda) * LeScale;
    if (rgbTable_.empty() || T > tableMax_) return blackbodyRGB(T) * LeScale;
    const float x = (T - kColdest) / (tableMax_ - kColdest) * float(kTableSize - 1);
    const int i = std::min(kTableSize - 2, int(x));
    const float f = std::min(1.0f, x - float(i));
    return (rgbTable_[size_t(i)] * (1 - f) + rgbTable_[size_t(i) + 1] * f) * LeScale;
}

}  // namespace ps
