// Spectra from scene files converted to the renderer's linear sRGB (D65 white), following
// pbrt-v4's normalisations (PBRT-CONVENTIONS §3, §6).
#pragma once
#include <optional>
#include <string>
#include <vector>
#include "math/spectrum.h"
#include "scene/params.h"

namespace ps {

// Piecewise-linear spectrum through (lambda[i], value[i]) (nm), zero outside the range.
// Albedo/Unbounded: reflectance-like, white-balanced so a flat 1 gives (1,1,1).
// Illuminant: normalised to luminance Y = 1, white-balanced so D65 gives (1,1,1).
Spectrum sampledSpectrumToRGB(const std::vector<float>& lambda, const std::vector<float>& value, SpectrumKind kind);

// Planck's law at temperature T (kelvin), normalised to luminance 1.
Spectrum blackbodyToRGB(float kelvin);

// pbrt-v4's named spectra (metal-*-eta/k, glass-*, stdillum-*); nullopt for unknown names.
std::optional<Spectrum> namedSpectrumToRGB(const std::string& name, SpectrumKind kind);

}  // namespace ps
