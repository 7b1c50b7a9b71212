// pbrt-v4's RGB colour spaces (the `ColorSpace` directive): the space of the RGB values
// parsed after it, and at `Film` the space of the output image. pathspace renders in linear
// sRGB (Rec. 709 primaries, D65 white); values of another space are converted into it by a
// 3x3 matrix through CIE XYZ, and the image out of it (PBRT-CONVENTIONS §2).
#pragma once
#include <array>
#include <string>

#include "math/spectrum.h"
#include "scene/params.h"
#include "spectral/rgb_color_space.h"  // the spaces themselves (namedColorSpace, srgbColorSpace)

namespace ps {

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
