// A density on [0,1]^2 that is bilinear between values on a regular grid, optionally
// conditioned on up to three parameters (multilinear between tabulated slices): the 2D warp
// of Dupuy & Jakob 2018 ("An Adaptive Parameterization for Efficient Material Acquisition
// and Rendering") that pbrt-v4's measured BRDF files are built on.
//
// Sampling inverts the marginal cdf (rows, y) and then the conditional cdf (columns, x);
// within a patch both are quadratics solved in closed form, so sample() and invert() are
// exact inverses and pdf() is the density of sample()'s output. The parameter lookup,
// interval search and clamping follow pbrt-v4's semantics, so files render as they do there.
#pragma once
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "math/vec.h"

namespace ps {

class PiecewiseLinear2D {
public:
    static constexpr int kMaxParams = 3;
    struct Result {
        Vec2 p;
        float pdf = 0;
    };
    // What the table is for: a warp (normalised to integrate to 1, with cdfs for sample()
    // and invert()), or an interpolant (values kept as given; only evaluate()).
    enum class Mode { Warp, Interpolant };

    PiecewiseLinear2D() = default;
    // `data` holds one xSize*ySize grid (row-major, y outer) per combination of parameter
    // values, the first parameter outermost. params[d] are the (strictly increasing)
    // positions of parameter d's slices. Throws std::invalid_argument for a grid below 2x2,
    // non-finite values, unsorted parameters, or (Warp) negative values or a slice whose
    // integral is not positive.
    PiecewiseLinear2D(const float* data, int xSize, int ySize, std::vector<std::vector<float>> params, Mode mode);

    // A point distributed with density pdf() from a uniform u (clamped away from 0 and 1).
    Result sample(Vec2 u, const float* param = nullptr) const;
    // The u that sample() maps to p, and the density at p.
    Result invert(Vec2 p, const float* param = nullptr) const;
    // The density (Warp) or the interpolated value (Interpolant) at p.
    float evaluate(Vec2 p, const float* param = nullptr) const;

    int xSize() const { return nx_; }
    int ySize() const { return ny_; }
    size_t bytes() const { return 4 * (data_.size() + marginal_.size() + conditional_.size()); }

private:
    // The slices around a parameter point and their multilinear weights.
    struct Slices {
        int n = 1;
        std::array<uint32_t, 1 << kMaxParams> index{};
        std::array<float, 1 << kMaxParams> weight{1.0f};
    };
    Slices slicesAt(const float* param) const;
    // Value i of per-slice arrays of `stride` values, interpolated between slices.
    static float lookup(const std::vector<float>& a, const Slices& s, uint32_t i, uint32_t stride) {
        float v = 0;
        for (int k = 0; k < s.n; ++k) v += s.weight[k] * a[s.index[k] * stride + i];
        return v;
    }
    // The density's values at the four corners of the cell whose first corner is value `at`.
    struct Corners {
        float v00, v10, v01, v11;
    };
    Corners cornersAt(const Slices& s, uint32_t at) const {
        const uint32_t n = uint32_t(nx_) * uint32_t(ny_);
        return {lookup(data_, s, at, n), lookup(data_, s, at + 1, n), lookup(data_, s, at + nx_, n),
                lookup(data_, s, at + nx_ + 1, n)};
    }

    int nx_ = 0, ny_ = 0;
    std::vector<std::vector<float>> params_;
    std::vector<float> data_;         // density (Warp, normalised) or values, per slice
    std::vector<float> marginal_;     // per slice: ny integrals of rows 0..y (Warp only)
    std::vector<float> conditional_;  // per slice and row: nx integrals of columns 0..x
};

}  // namespace ps
