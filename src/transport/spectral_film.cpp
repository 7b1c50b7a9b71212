#include "transport/spectral_film.h"

#include "spectral/cie.h"
#include "transport/integrator.h"
#include "util/error.h"

namespace ps {

Matrix3 renderingFromSensor(const RenderSettings& settings) {
    // The sensor's imaging ratio stays 1: RenderSettings::imagingRatio scales both modes.
    SensorSettings s;
    s.whiteBalance = settings.spectral ? settings.whiteBalance : 0;  // RGB mode does not white-balance
    const RGBColorSpace& output = settings.filmColorSpace ? *settings.filmColorSpace : srgbColorSpace();
    Matrix3 m = Sensor::create(s, output).sensor.outputFromSensor();
    // The film holds the rendering space (linear sRGB) and converts to its colour space when
    // it writes the image: undo that conversion here.
    if (const auto& out = settings.outputColorMatrix) {
        Matrix3 o;
        for (int k = 0; k < 9; ++k) o.a[k / 3][k % 3] = (*out)[size_t(k)];
        m = o.inverse() * m;
    }
    return m;
}

ClampSpace sensorFromRendering(const RenderSettings& settings) {
    const Matrix3 m = renderingFromSensor(settings).inverse();
    ClampSpace c{};
    for (size_t k = 0; k < 9; ++k) c[k] = float(m.a[k / 3][k % 3]);
    return c;
}

void setChainClamp(Film& film, const RenderSettings& settings) {
    film.setChainMaxComponentValue(settings.maxComponentValue, settings.imagingRatio, sensorFromRendering(settings));
}

SpectralFilm::SpectralFilm(const RenderSettings& settings) {
    const Matrix3 m = renderingFromSensor(settings);
    // The rendering space's RGB matching functions on the 1 nm grid.
    for (int k = 0; k < kCieSamples; ++k) {
        const auto v = m * std::array<double, 3>{kCieX[k], kCieY[k], kCieZ[k]};
        renderingCmf_[size_t(k)] = {float(v[0]), float(v[1]), float(v[2])};
    }
}

Spectrum SpectralFilm::toRendering(const Spectrum& L, const SampledWavelengths& w) const {
    // The sensor's estimate (Sensor::toSensorXYZ: the mean over the wavelengths of
    // cmf(lambda) L / pdf, pdf 0 skipped) with the matching functions already taken to the
    // rendering space (renderingCmf_), in float: this runs once per camera sample.
    float rgb[3] = {0, 0, 0};
    for (int i = 0; i < kWavelengthSamples; ++i) {
        const float pdf = w.pdf[size_t(i)];
        const int k = cieIndex(w.lambda[size_t(i)]);
        if (pdf == 0 || k < 0) continue;
        const float v = L[i] / pdf;
        for (int c = 0; c < 3; ++c) rgb[c] += renderingCmf_[size_t(k)][size_t(c)] * v;
    }
    return {rgb[0] * (1.0f / kWavelengthSamples), rgb[1] * (1.0f / kWavelengthSamples), rgb[2] * (1.0f / kWavelengthSamples)};
}

Spectrum SampleContext::toFilm(const Spectrum& L) const { return sensor ? sensor->toRendering(L, *lambda) : L; }

void requireSpectralSupport(const Integrator& integrator, const std::string& integratorName) {
    if (!integrator.supportsSpectral())
        throw InputError("--color spectral: integrator \"" + integratorName + "\" renders in RGB only (use --color rgb)");
}

}  // namespace ps
