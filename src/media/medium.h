// Participating media as pbrt-v4 defines them (media.h): at each point an absorption and a
// scattering coefficient, an emitted radiance and a Henyey-Greenstein phase function, and
// along any ray a majorant sigma_maj >= sigma_a + sigma_s that delta and ratio tracking
// sample against (Novak et al. 2014; pbrt-v4's SampleT_maj).
#pragma once
#include <cmath>
#include "math/spectrum.h"
#include "math/vec.h"
#include "materials/phase_function.h"
#include "spectral/sampled_spectrum.h"

namespace ps {

struct MediumProperties {
    Spectrum sigmaA, sigmaS, Le;
};

// A part of a ray, in distance along its unit direction, where a medium may interact, with
// the majorant that bounds sigma_t over it.
struct MajorantSegment {
    float t0 = 0, t1 = 0;
    Spectrum sigmaMaj;
};

class MajorantIterator;
class DensityMedium;

// A scene spectrum in both colour modes: an RGB value, or a spectrum's values at a path's
// wavelengths (spectral mode, lambda not null) times a scale.
class MediumSpectrum {
public:
    MediumSpectrum() = default;
    MediumSpectrum(Spectrum rgb, SpectrumSource s, float spectralScale) : rgb_(rgb), src_(std::move(s)), scale_(spectralScale) {}
    Spectrum operator()(const SampledWavelengths* lambda) const {
        return lambda ? sampleSpectrum(src_, *lambda) * scale_ : rgb_;
    }
    float maxValue() const { return std::max(rgb_.maxComponent(), src_.maxValue() * scale_); }

private:
    Spectrum rgb_;
    SpectrumSource src_ = SpectrumSource::constant(0);
    float scale_ = 0;
};

class Medium {
public:
    explicit Medium(float g) : phase_(g) {}
    virtual ~Medium() = default;
    const HGPhaseFunction& phase() const { return phase_; }
    virtual bool emissive() const { return false; }
    // The coefficients at a world-space point.
    virtual MediumProperties at(Vec3 p, const SampledWavelengths* lambda) const = 0;
    // The segments of o + t d (d unit, t in [0, tMax]) where the medium can interact, each
    // with a majorant that bounds sigma_t over it (pbrt-v4's SampleRay); none where the ray
    // misses a grid's box.
    virtual MajorantIterator majorants(Vec3 o, Vec3 d, float tMax, const SampledWavelengths* lambda) const = 0;
    // Itself when its sigma_a and sigma_s are a density times two fixed spectra.
    virtual const DensityMedium* asDensityMedium() const { return nullptr; }

private:
    HGPhaseFunction phase_;
};

inline Spectrum expNeg(const Spectrum& s) {
    // A grey exponent (a grey medium's majorant, in either colour mode) needs one exp.
    if (s.r == s.g && s.r == s.b && s.r == s.c3) return Spectrum(std::exp(-s.r));
    return Spectrum::sampled(std::exp(-s.r), std::exp(-s.g), std::exp(-s.b), std::exp(-s.c3));
}
inline Spectrum clampZero(const Spectrum& s) {
    return Spectrum::sampled(std::max(0.0f, s.r), std::max(0.0f, s.g), std::max(0.0f, s.b), std::max(0.0f, s.c3));
}
// The mean over the channels that carry colour: the four wavelengths in spectral mode, r, g
// and b in RGB mode (whose fourth channel copies g). Spectral MIS (pbrt-v4's volpath) divides
// by the mean of the channels' path densities.
inline float channelMean(const Spectrum& s, bool spectral) {
    return spectral ? (s.r + s.g + s.b + s.c3) * 0.25f : s.average();
}

}  // namespace ps
