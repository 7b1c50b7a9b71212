// Spectral mode (`--color spectral`, math/spectrum.h) between the estimator and the film:
// each camera sample draws its wavelengths, and the radiance the path brings back at them
// goes through the film's sensor (pbrt-v4's PixelSensor, cie1931 with white balance) to the
// rendering space's RGB before it reaches the film, so that the film, its variance, adaptive
// sampling and the AOVs see colour as in RGB mode.
#pragma once
#include <array>

#include "film/film.h"
#include "math/matrix3.h"
#include "math/spectrum.h"
#include "render/scene.h"
#include "spectral/cie.h"
#include "spectral/sensor.h"
#include "spectral/wavelengths.h"

namespace ps {

class Integrator;

class SpectralFilm {
public:
    explicit SpectralFilm(const RenderSettings& settings);
    // pbrt-v4's SampleVisible: four wavelengths stratified from one sample dimension.
    static SampledWavelengths sampleWavelengths(float u) { return SampledWavelengths::sampleVisible(u); }
    // The rendering space's linear RGB (before the imaging ratio, which the caller applies as in
    // RGB mode) of radiance L at w; wavelengths with pdf 0 (terminated) contribute nothing.
    Spectrum toRendering(const Spectrum& L, const SampledWavelengths& w) const;

private:
    // The CIE matching functions at each whole nanometre taken through the sensor's output
    // matrix (white balance included) to the rendering space; the sensor's imaging ratio is 1.
    std::array<std::array<float, 3>, kCieSamples> renderingCmf_;
};

// The film's linear RGB (the rendering space) from the sensor's (pbrt-v4's PixelSensor: XYZ
// for its "cie1931" sensor) and back: white balance (spectral mode only), the output colour
// space and its undoing by the film included. The inverse is where Film "maxcomponentvalue"
// measures a sample's components, in both modes.
Matrix3 renderingFromSensor(const RenderSettings& settings);
ClampSpace sensorFromRendering(const RenderSettings& settings);
// Film "maxcomponentvalue" on the film of a Markov chain (Film::setChainMaxComponentValue).
void setChainClamp(Film& film, const RenderSettings& settings);

// Throws InputError, naming the integrator, unless it supports spectral mode (every light and
// material does).
void requireSpectralSupport(const Integrator& integrator, const std::string& integratorName);

}  // namespace ps
