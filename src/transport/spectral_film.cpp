#include "transport/spectral_film.h"

#include "transport/integrator.h"
#include "util/error.h"

namespace ps {

SpectralFilm::SpectralFilm(const RenderSettings& settings) {
    // The sensor's imaging ratio stays 1: RenderSettings::imagingRatio scales both modes.
    SensorSettings s;
    s.whiteBalance = settings.whiteBalance;
    const RGBColorSpace& output = settings.filmColorSpace ? *settings.filmColorSpace : srgbColorSpace();
    sensor_ = Sensor::create(s, output).sensor;
    Matrix3 m = sensor_.outputFromSensor();
    // The film holds the rendering space (linear sRGB) and converts to its colour space when
    // it writes the image: undo that conversion here.
    if (const auto& out = settings.outputColorMatrix) {
        Matrix3 o;
        for (int k = 0; k < 9; ++k) o.a[k / 3][k % 3] = (*out)[size_t(k)];
        m = o.inverse() * m;
    }
    renderingFromXYZ_ = m;
}

Spectrum SpectralFilm::toRendering(const Spectrum& L, const SampledWavelengths& w) const {
    const auto xyz = sensor_.toSensorXYZ({L[0], L[1], L[2], L[3]}, w);
    const auto rgb = renderingFromXYZ_ * xyz;
    return {float(rgb[0]), float(rgb[1]), float(rgb[2])};
}

void requireSpectralSupport(const Scene& scene, const Integrator& integrator, const std::string& integratorName) {
    if (!integrator.supportsSpectral())
        throw InputError("--color spectral is supported by --integrator path only for now; \"" + integratorName +
                         "\" renders in RGB (use --color rgb)");
    for (const auto& light : scene.lights())
        if (!light->supportsSpectral())
            throw InputError("--color spectral: the scene has a goniometric or projection light, which renders in RGB "
                             "only for now (use --color rgb)");
    for (const auto& material : scene.materials())
        if (const char* name = material->rgbOnly())
            throw InputError(std::string("--color spectral: the \"") + name +
                             "\" material renders in RGB only for now (use --color rgb)");
}

}  // namespace ps
