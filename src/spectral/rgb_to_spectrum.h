// RGB to sigmoid-polynomial lookup in a coefficient table built at build time by
// gen/rgb2spec_gen.cpp (pbrt-v4's RGBToSpectrumTable semantics).
#pragma once
#include <array>
#include <cstdint>

#include "spectral/rgb_color_space.h"
#include "spectral/sigmoid_polynomial.h"

namespace ps {

class RGBToSpectrumTable {
  public:
    // The table of a named colour space (embedded in the library).
    static const RGBToSpectrumTable& forSpace(const RGBColorSpace& space);

    // rgb in [0,1]^3 (clamped; NaN counts as 0). Equal components are exact: the constant c2 with S(c2) = v,
    // so black, white and greys are reproduced exactly; otherwise trilinear interpolation
    // of the coefficients in (x, y, brightness) as pbrt-v4.
    SigmoidPolynomial operator()(std::array<float, 3> rgb) const;

    // FNV-1a of the table's bytes and the value the generator recorded for them.
    uint64_t checksum() const;
    uint64_t expectedChecksum() const { return expected_; }

  private:
    RGBToSpectrumTable(const float* coefficients, uint64_t expected);
    const float* coefficients_;
    uint64_t expected_;
    std::array<float, 64> brightness_;
};

}  // namespace ps
