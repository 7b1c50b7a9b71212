// The tables of a measured BRDF file (pbrt-v4's `Material "measured"`, the RGL database's
// .bsdf format of Dupuy & Jakob 2018): the reflectance both converted to RGB (RGB mode) and,
// for spectral files, as tabulated (spectral mode).
#pragma once
#include <memory>
#include <string>

#include "mc/piecewise_linear_2d.h"

namespace ps {

struct MeasuredBRDF {
    // All are functions of the unit square's (theta, phi) coordinates u = (sqrt(2 theta / pi),
    // phi / 2pi + 1/2); the parameterised ones take (phi_o, theta_o) of the outgoing direction.
    PiecewiseLinear2D ndf;        // D(wm) (interpolant)
    PiecewiseLinear2D sigma;      // projected microfacet area of wo (interpolant)
    PiecewiseLinear2D vndf;       // warp: visible normals seen from wo
    PiecewiseLinear2D luminance;  // warp: luminance of the reflectance in vndf's sample space
    PiecewiseLinear2D rgb;        // the reflectance in that space, parameters (phi_o, theta_o, channel)
    // The file's `spectra` (absent in RGB files): the same with parameters (phi_o, theta_o,
    // lambda), interpolated linearly in lambda and constant beyond the tabulated range, as
    // pbrt-v4 evaluates it at each of a path's wavelengths.
    PiecewiseLinear2D spectra;
    bool hasSpectra = false;
    bool isotropic = true;        // tabulated for one phi_o (at most 2 values): phi is relative to phi_o

    // Reads the file, with errors "PATH: ..." naming the field at fault (InputError, no
    // location: the caller adds the directive's). The reflectance is the file's `rgb` field
    // when present, else `spectra` at `wavelengths` converted to RGB (reflectanceSampleWeights).
    // Files are read once per path and shared.
    static std::shared_ptr<const MeasuredBRDF> load(const std::string& path);
};

}  // namespace ps
