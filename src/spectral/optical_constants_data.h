// Tabulated refractive indices of pbrt-v4's named metals and glasses (sources in
// optical_constants_data.cpp).
#pragma once
#include <cmath>
#include <span>
#include <string_view>

namespace ps {

// Interleaved (wavelength nm, value) pairs for "metal-{Ag,Al,Au,Cu,CuZn,MgO,TiO2}-{eta,k}"
// and "glass-{BK7,BAF10,FK51A,LASF9,F5,F10,F11}"; empty for another name.
std::span<const float> opticalConstantPairs(std::string_view name);

// A glass' Sellmeier dispersion formula, n^2 = 1 + sum B_i l^2 / (l^2 - C_i) (l in um):
// the closed form behind the tables, for checks and for analytic dispersion.
struct SellmeierGlass {
    std::string_view name;
    double b[3], c[3];
    double nd;  // catalogue index at the helium d line, 587.56 nm
    double index(double lambdaNm) const;
};
const SellmeierGlass* sellmeierGlass(std::string_view name);

}  // namespace ps
