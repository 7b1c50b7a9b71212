// The sRGB transfer curve (IEC 61966-2-1): linear segment near black, 2.4 power above.
#include <algorithm>
#include <cmath>
#include "image/image.h"

namespace ps {

// Evaluated in double so the float results are correctly rounded.
float srgbToLinear(float v) {
    double x = v;
    if (x <= 0.04045) return float(x / 12.92);
    return float(std::pow((x + 0.055) / 1.055, 2.4));
}

float linearToSrgb(float v) {
    double x = v;
    constexpr double kBreak = 0.0031308;
    if (x <= kBreak) return float(x * 12.92);
    // The standard's two segments do not quite meet: just above kBreak the power segment
    // is ~3e-8 below the linear one. Holding it at the joint keeps the curve monotonic.
    return float(std::max(1.055 * std::pow(x, 1.0 / 2.4) - 0.055, kBreak * 12.92));
}

}  // namespace ps
