// pbrt-v4's RGB colour spaces (the `ColorSpace` directive): the space of the RGB values
// parsed after it, and at `Film` the space of the output image. pathspace renders in linear
// sRGB (Rec. 709 primaries, D65 white); values of another space are converted into it by a
// 3x3 matrix through CIE XYZ, and the image out of it (PBRT-CONVENTIONS §2).
#pragma once
#include <array>
#include <string>

#include "math/spectrum.h"
#include "scene/params.h"

namespace ps {

struct RGBColorSpace {
    const char* name;
    double primaries[3][2];  // chromaticities (x, y) of R, G, B
    double white[2];         // of the space's standard illuminant
};

// "srgb", "rec2020", "dci-p3" (P3 primaries with D65, as pbrt-v4) or "aces2065-1" (AP0
// primaries, the ACES D60 white), case-insensitive; null for another name.
const RGBColorSpace* namedColorSpace(const std::string& name);
const RGBColorSpace& srgbColorSpace();

// A value of `space` as the renderer's linear sRGB, by its use (pbrt-v4 lifts each use to a
// spectrum differently):
//  Illuminant: the emission's colour itself, RGB -> XYZ -> sRGB, so an RGB white in ACES
//              emits the ACES (D60) white, slightly warmer than sRGB's;
//  Albedo, Unbounded: white stays white (a reflectance of 1 reflects everything, in any
//              space), through a Bradford adaptation from the space's white to D65.
// Colours outside sRGB's gamut are clipped to 0, reflectances also to 1. The identity for
// sRGB (and a null space).
Spectrum toRenderingSpace(Spectrum rgb, const RGBColorSpace* space, SpectrumKind kind);

// The matrix (row-major) from the renderer's linear sRGB to `space`'s RGB, for the film's
// output: pbrt-v4 converts the sensor's XYZ with the film colour space's RGB-from-XYZ.
std::array<float, 9> outputFromRenderingSpace(const RGBColorSpace& space);

}  // namespace ps
