// Tabulated spectra: linear interpolation between (wavelength, value) samples, as pbrt-v4's
// PiecewiseLinearSpectrum, and its extension of named tables to the visible range.
#pragma once
#include <span>
#include <vector>

namespace ps {

struct PiecewiseLinearTable {
    std::vector<float> lambda, value;  // lambda strictly increasing

    // Linear interpolation; zero outside [lambda.front(), lambda.back()] (pbrt-v4).
    float at(float l) const;
    float maxValue() const;

    // pbrt-v4's PiecewiseLinearSpectrum::FromInterleaved: (lambda, value) pairs, extended by
    // a sample at 359 nm holding the first value when the table starts above 360 nm and one
    // at 831 nm holding the last when it ends below 830 nm, so that a named table is never
    // cut to zero inside the visible range. With `normalize`, scaled so that its luminance
    // sum over the 1 nm grid, sum ybar * s, equals kCieYIntegral (i.e. its Y is 1).
    static PiecewiseLinearTable fromInterleaved(std::span<const float> pairs, bool normalize);
};

}  // namespace ps
