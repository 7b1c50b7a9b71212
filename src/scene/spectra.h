// Spectra from scene files converted to the renderer's linear sRGB (D65 white), following
// pbrt-v4's normalisations (PBRT-CONVENTIONS §2, §3, §6).
#pragma once
#include <optional>
#include <string>
#include <vector>
#include "math/spectrum.h"
#include "scene/params.h"

namespace ps {

// Piecewise-linear spectrum through (lambda[i], value[i]) (nm, increasing), zero outside
// the given range, converted according to its use:
//  Albedo:     reflectance under D65 relative to a perfect white, so a flat 1 gives (1,1,1);
//              values are clamped to [0,1] per wavelength and per channel (pbrt clamps
//              reflectances when it evaluates them).
//  Illuminant: only the chromaticity counts; normalised to luminance Y = 1 (§3: pbrt divides
//              spectral emission by its photometric integral). D65 gives (1,1,1).
//  Unbounded:  per-channel averages over the R, G, B bands (weights: the positive parts of
//              the sRGB colour matching functions), so a flat spectrum stays flat and values
//              stay non-negative (conductor eta/k, spectral IOR).
Spectrum sampledSpectrumToRGB(const std::vector<float>& lambda, const std::vector<float>& value, SpectrumKind kind);

// Linear weights for reflectance spectra tabulated at `lambda` (nm, increasing): the RGB
// of the spectrum through (lambda[k], v[k]) is the sum of v[k] * weights[k]. Like Albedo but
// held constant beyond the first and last sample (not zero) and without clamping, so it
// stays linear: a flat spectrum v gives (v, v, v).
std::vector<Spectrum> reflectanceSampleWeights(const std::vector<float>& lambda);

// True when the piecewise-linear spectrum has one value over the whole visible range
// [360, 830] nm (it is zero outside its samples, so it must cover that range).
bool sampledSpectrumIsConstant(const std::vector<float>& lambda, const std::vector<float>& value);

// Planck's law at T kelvin. As an illuminant: luminance 1 (§3). Otherwise pbrt's blackbody
// spectrum normalised to a peak of 1, converted as above.
Spectrum blackbodyToRGB(float kelvin);
Spectrum blackbodyToRGB(float kelvin, SpectrumKind kind);

// pbrt-v4's named spectra: metal-{Ag,Al,Au,Cu,CuZn,MgO,TiO2}-{eta,k} (per-channel values),
// glass-{BK7,BAF10,FK51A,LASF9,F5,F10,F11} (flat index at 587.6 nm), stdillum-{A,D50,D65,
// F1..F12} and illum-acesD60 (chromaticity, luminance 1). nullopt for unknown names.
std::optional<Spectrum> namedSpectrumToRGB(const std::string& name, SpectrumKind kind);

// CIE XYZ to linear sRGB (D65 white).
Spectrum xyzToLinearSRGB(double X, double Y, double Z);
// Colour of chromaticity (x, y) at luminance 1, white-balanced so D65's (x, y) gives (1,1,1).
Spectrum chromaticityToRGB(double x, double y);

// Reads a spectrum file: whitespace-separated wavelength/value pairs, '#' comments.
// Returns "" on success, else what is wrong (the caller adds the location).
std::string readSpectrumFile(const std::string& path, std::vector<float>& lambda, std::vector<float>& value);

}  // namespace ps
