// pbrt-v4's named spectra (GetNamedSpectrum) with their full tabulated data: metal-*-eta/k,
// glass-*, stdillum-* and illum-acesD60. The camera sensor curves pbrt also names are not
// included (see sensor.h).
#pragma once
#include <optional>
#include <string>

#include "spectral/spectrum_source.h"

namespace ps {

// Tables extended flat to cover 360..830 nm (pbrt's FromInterleaved); the illuminants are
// normalised to luminance 1 (sum ybar * s over the 1 nm grid = kCieYIntegral), the
// metals and glasses are not. nullopt for an unknown name (case-sensitive, as pbrt).
std::optional<SpectrumSource> namedSpectrum(const std::string& name);

}  // namespace ps
