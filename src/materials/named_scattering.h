// pbrt-v4's named measured scattering coefficients (media.cpp: GetMediumScatteringProperties),
// read by the `subsurface` material's "name" and the homogeneous medium's "preset": Jensen et
// al. 2001 ("A Practical Model for Subsurface Light Transport") and Narasimhan et al. 2006
// ("Acquiring Scattering Properties of Participating Media by Dilution"), in mm^-1. The
// scattering values are reduced coefficients sigma_s' = sigma_s (1 - g), so they go with g = 0.
// pbrt-v4 lifts both as sRGB unbounded spectra.
#pragma once
#include <array>
#include <optional>
#include <string>

#include "media/medium.h"

namespace ps {

struct NamedScattering {
    std::array<float, 3> sigmaA, sigmaS;  // sRGB
};

// The entry of that name (case-sensitive, as pbrt-v4), or nullopt.
std::optional<NamedScattering> namedScattering(const std::string& name);
// An sRGB coefficient (an entry's, or pbrt-v4's default) times `scale`, in both colour modes
// (spectral: pbrt-v4's RGBUnboundedSpectrum in sRGB).
MediumSpectrum srgbCoefficient(const std::array<float, 3>& rgb, float scale);
// Every name, quoted and comma-separated, for messages.
std::string namedScatteringList();

}  // namespace ps
