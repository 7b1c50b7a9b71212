// Tabulated standard illuminants (sources in illuminant_data.cpp).
#pragma once
#include <span>
#include <string_view>

namespace ps {

// Interleaved (wavelength nm, relative power) pairs, unnormalised, of pbrt-v4's named
// illuminants: "stdillum-A", "stdillum-D50", "stdillum-D65", "stdillum-F1".."stdillum-F12",
// "illum-acesD60". Empty for another name.
std::span<const float> standardIlluminantPairs(std::string_view name);

// The CIE daylight basis S0, S1, S2 at kDSeriesLambda (300..830 nm, 5 nm).
constexpr int kDSeriesSamples = 107;
extern const float kDSeriesLambda[kDSeriesSamples];
extern const float kDSeriesS0[kDSeriesSamples];
extern const float kDSeriesS1[kDSeriesSamples];
extern const float kDSeriesS2[kDSeriesSamples];

}  // namespace ps
