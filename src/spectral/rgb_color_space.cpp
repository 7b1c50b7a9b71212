#include "spectral/rgb_color_space.h"

#include <algorithm>
#include <cctype>

namespace ps {

namespace {

// ITU-R BT.709 (sRGB), ITU-R BT.2020, SMPTE EG 432-1 (P3-D65), SMPTE ST 2065-1 (ACES AP0).
const RGBColorSpace kSpaces[kNamedColorSpaces] = {
    {"srgb", {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}}, {0.3127, 0.3290}, "stdillum-D65", 0},
    {"rec2020", {{0.708, 0.292}, {0.170, 0.797}, {0.131, 0.046}}, {0.3127, 0.3290}, "stdillum-D65", 1},
    {"dci-p3", {{0.680, 0.320}, {0.265, 0.690}, {0.150, 0.060}}, {0.3127, 0.3290}, "stdillum-D65", 2},
    {"aces2065-1", {{0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.077}}, {0.32168, 0.33767}, "illum-acesD60", 3},
};

}  // namespace

const RGBColorSpace& srgbColorSpace() { return kSpaces[0]; }
const RGBColorSpace& colorSpaceByIndex(int index) { return kSpaces[index]; }

const RGBColorSpace* namedColorSpace(const std::string& name) {
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    for (const RGBColorSpace& s : kSpaces)
        if (lower == s.name) return &s;
    return nullptr;
}

}  // namespace ps
