// pbrt-v4's named RGB colour spaces (the `ColorSpace` directive and the film's output
// space): primaries, nominal white and the standard illuminant that defines each.
#pragma once
#include <string>

namespace ps {

struct RGBColorSpace {
    const char* name;
    double primaries[3][2];  // chromaticities (x, y) of R, G, B
    double white[2];         // nominal chromaticity of the standard illuminant
    const char* illuminant;  // pbrt-v4's name of the standard illuminant's spectrum
    int index;               // position in the list below (0 = srgb)
};

constexpr int kNamedColorSpaces = 4;

// "srgb", "rec2020", "dci-p3" (P3 primaries with D65, as pbrt-v4) or "aces2065-1" (AP0
// primaries, the ACES D60 white), case-insensitive; null for another name.
const RGBColorSpace* namedColorSpace(const std::string& name);
const RGBColorSpace& srgbColorSpace();
const RGBColorSpace& colorSpaceByIndex(int index);

}  // namespace ps
