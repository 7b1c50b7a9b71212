// Scene spectra at a path's sampled wavelengths, as the path's Spectrum (spectral mode; see
// math/spectrum.h): a SpectrumSource evaluated, or an RGB value lifted per lookup the way
// pbrt-v4 lifts the RGB of image textures and emission images (RGBAlbedoSpectrum,
// RGBUnboundedSpectrum, RGBIlluminantSpectrum built at each lookup).
#pragma once
#include "math/spectrum.h"
#include "spectral/rgb_color_space.h"
#include "spectral/spectrum_source.h"
#include "spectral/wavelengths.h"

namespace ps {

Spectrum sampleSpectrum(const SpectrumSource& s, const SampledWavelengths& w);

// `rgb` (channels 0..2, linear, in `space`) lifted and evaluated at w. Albedo clamps to [0,1];
// the illuminant form is divided by the photometric integral of the space's illuminant, as
// pbrt-v4's lights divide their scale, so that RGB (1,1,1) emits Y = 1.
Spectrum liftAlbedo(const Spectrum& rgb, const SampledWavelengths& w, const RGBColorSpace& space = srgbColorSpace());
Spectrum liftUnbounded(const Spectrum& rgb, const SampledWavelengths& w, const RGBColorSpace& space = srgbColorSpace());
Spectrum liftIlluminant(const Spectrum& rgb, const SampledWavelengths& w, const RGBColorSpace& space = srgbColorSpace());

}  // namespace ps
