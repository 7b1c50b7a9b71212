// The CIE 1931 2-degree colour matching functions at 1 nm over [360, 830] nm and lookups
// that behave like pbrt-v4's DenselySampledSpectrum (the value at the nearest whole
// nanometre, zero outside the table).
#pragma once
#include <cmath>

namespace ps {

constexpr int kCieLambdaMin = 360, kCieLambdaMax = 830;
constexpr int kCieSamples = kCieLambdaMax - kCieLambdaMin + 1;

// The sum of ybar over the table (1 nm steps): the Y of a flat spectrum of value 1. pbrt-v4's
// constant (CIE_Y_integral), which differs from the double-precision sum 106.8569171 of the
// same table in the 7th digit; it only scales, so it is kept identical.
constexpr float kCieYIntegral = 106.856895f;

// CIE 015:2004 "Colorimetry", 3rd ed., table T.4: the CIE 1931 standard colorimetric
// observer, 1 nm (also CIE dataset doi:10.25039/CIE.DS.xvudnb9b). Index i is 360 + i nm.
extern const float kCieX[kCieSamples];
extern const float kCieY[kCieSamples];
extern const float kCieZ[kCieSamples];

// Index of the 1 nm sample nearest to lambda, or -1 outside the table (pbrt rounds with
// lround, halves away from zero).
inline int cieIndex(float lambda) {
    // Halves away from zero is floor(lambda + 1/2) for the positive values that can hit the
    // table, without lround's library call (this runs per wavelength at every light and
    // film sample); NaN and negative values fall outside.
    if (!(lambda >= kCieLambdaMin - 0.5f && lambda < kCieLambdaMax + 0.5f)) return -1;
    return int(lambda + 0.5f) - kCieLambdaMin;
}
inline float denseLookup(const float* table, float lambda) {
    const int i = cieIndex(lambda);
    return i < 0 ? 0.0f : table[i];
}

}  // namespace ps
