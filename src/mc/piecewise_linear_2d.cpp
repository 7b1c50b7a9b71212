#include "mc/piecewise_linear_2d.h"

#include <cmath>
#include <string>

namespace ps {

namespace {

// The last i in [0, n-2] where pred(i) holds (pred holds on a prefix), 0 when none does.
template <typename Pred>
uint32_t findInterval(uint32_t n, Pred pred) {
    uint32_t first = 0, count = n;  // binary search for the first index where pred fails
    while (count > 0) {
        uint32_t half = count / 2, mid = first + half;
        if (pred(mid)) {
            first = mid + 1;
            count -= half + 1;
        } else {
            count = half;
        }
    }
    return first == 0 ? 0 : std::min(first - 1, n - 2);
}

// The root t in [0,1] of a0 t + (a1 - a0) t^2 / 2 = v: where the integral of the linear
// density a0..a1 over [0,t] reaches v (the inverse of a trapezoid's cdf).
float solveLinearCdf(float a0, float a1, float v) {
    if (std::fabs(a0 - a1) < 1e-4f * (a0 + a1)) return 2 * v / (a0 + a1);
    return (a0 - std::sqrt(std::max(0.0f, a0 * a0 - 2 * v * (a0 - a1)))) / (a0 - a1);
}

// The patch holding p (the last one for p beyond the grid, extrapolating as pbrt-v4 does)
// and p's offsets in it, in patch units.
struct Patch {
    uint32_t col = 0, row = 0;
    float fx = 0, fy = 0;
};
Patch patchAt(Vec2 p, int nx, int ny) {
    Patch q;
    float fx = p.x * float(nx - 1), fy = p.y * float(ny - 1);
    if (!std::isfinite(fx) || !std::isfinite(fy)) return q;  // int() of these is undefined
    q.col = uint32_t(std::clamp(int(std::clamp(fx, -1.0f, float(nx))), 0, nx - 2));
    q.row = uint32_t(std::clamp(int(std::clamp(fy, -1.0f, float(ny))), 0, ny - 2));
    q.fx = fx - float(q.col);
    q.fy = fy - float(q.row);
    return q;
}

}  // namespace

PiecewiseLinear2D::PiecewiseLinear2D(const float* data, int xSize, int ySize, std::vector<std::vector<float>> params, Mode mode)
    : nx_(xSize), ny_(ySize), params_(std::move(params)) {
    if (nx_ < 2 || ny_ < 2) throw std::invalid_argument("the grid must be at least 2x2");
    if (params_.size() > size_t(kMaxParams)) throw std::invalid_argument("more than 3 parameters");
    size_t slices = 1;
    for (const auto& p : params_) {
        if (p.empty()) throw std::invalid_argument("a parameter has no values");
        for (size_t i = 0; i < p.size(); ++i)
            if (!std::isfinite(p[i]) || (i > 0 && !(p[i] > p[i - 1])))
                throw std::invalid_argument("parameter values must be finite and strictly increasing");
        slices *= p.size();
    }
    const size_t n = size_t(nx_) * ny_;
    data_.assign(data, data + slices * n);
    for (float v : data_)
        if (!std::isfinite(v) || (mode == Mode::Warp && v < 0))
            throw std::invalid_argument(mode == Mode::Warp ? "density values must be finite and non-negative" : "values must be finite");
    if (mode == Mode::Interpolant) return;

    marginal_.resize(slices * ny_);
    conditional_.resize(slices * n);
    for (size_t s = 0; s < slices; ++s) {
        float* d = &data_[s * n];
        float* cond = &conditional_[s * n];
        float* marg = &marginal_[s * ny_];
        // Each patch counts as one unit of area here; pdfs scale by the patch count.
        for (int y = 0; y < ny_; ++y) {
            double sum = 0;
            cond[y * nx_] = 0;
            for (int x = 0; x + 1 < nx_; ++x) {
                sum += 0.5 * (double(d[y * nx_ + x]) + d[y * nx_ + x + 1]);
                cond[y * nx_ + x + 1] = float(sum);
            }
        }
        double sum = 0;
        marg[0] = 0;
        for (int y = 0; y + 1 < ny_; ++y) {
            sum += 0.5 * (double(cond[(y + 1) * nx_ - 1]) + cond[(y + 2) * nx_ - 1]);
            marg[y + 1] = float(sum);
        }
        if (!(sum > 0) || !std::isfinite(sum)) throw std::invalid_argument("a slice of the density integrates to zero");
        float norm = float(1 / sum);
        for (size_t i = 0; i < n; ++i) {
            cond[i] *= norm;
            d[i] *= norm;
        }
        for (int y = 0; y < ny_; ++y) marg[y] *= norm;
    }
}

PiecewiseLinear2D::Slices PiecewiseLinear2D::slicesAt(const float* param) const {
    Slices s;
    // Parameters are laid out with the last one innermost.
    uint32_t stride = 1;
    for (int d = int(params_.size()) - 1; d >= 0; --d) {
        const std::vector<float>& v = params_[d];
        const uint32_t size = uint32_t(v.size());
        if (size > 1) {
            float x = param[d];
            uint32_t i = findInterval(size, [&](uint32_t k) { return v[k] <= x; });
            // Clamped weights: constant beyond the first and last slice (NaN -> the first).
            float t = (x - v[i]) / (v[i + 1] - v[i]);
            t = t > 0 ? std::min(t, 1.0f) : 0.0f;
            for (int k = 0; k < s.n; ++k) {
                s.index[k + s.n] = s.index[k] + (i + 1) * stride;
                s.weight[k + s.n] = s.weight[k] * t;
                s.index[k] += i * stride;
                s.weight[k] *= 1 - t;
            }
            s.n *= 2;
        }
        stride *= size;
    }
    return s;
}

PiecewiseLinear2D::Result PiecewiseLinear2D::sample(Vec2 u, const float* param) const {
    const float lo = 0x1p-24f, hi = 1 - 0x1p-24f;
    u.x = u.x > lo ? std::min(u.x, hi) : lo;
    u.y = u.y > lo ? std::min(u.y, hi) : lo;
    const Slices s = slicesAt(param);
    const uint32_t n = uint32_t(nx_) * ny_;

    // Row: the marginal cdf, then the linear density across the row's patch.
    uint32_t row = findInterval(ny_, [&](uint32_t i) { return lookup(marginal_, s, i, ny_) < u.y; });
    u.y -= lookup(marginal_, s, row, ny_);
    const uint32_t rowStart = row * nx_;
    float r0 = lookup(conditional_, s, rowStart + nx_ - 1, n), r1 = lookup(conditional_, s, rowStart + 2 * nx_ - 1, n);
    const float ty = solveLinearCdf(r0, r1, u.y);

    // Column: the conditional cdf at that height, then the same within the patch.
    u.x *= (1 - ty) * r0 + ty * r1;
    auto conditional = [&](uint32_t i) {
        return (1 - ty) * lookup(conditional_, s, rowStart + i, n) + ty * lookup(conditional_, s, rowStart + nx_ + i, n);
    };
    uint32_t col = findInterval(nx_, [&](uint32_t i) { return conditional(i) < u.x; });
    u.x -= conditional(col);
    const uint32_t at = rowStart + col;
    const auto [v00, v10, v01, v11] = cornersAt(s, at);
    float c0 = (1 - ty) * v00 + ty * v01, c1 = (1 - ty) * v10 + ty * v11;
    const float tx = solveLinearCdf(c0, c1, u.x);
    return {Vec2((col + tx) / float(nx_ - 1), (row + ty) / float(ny_ - 1)), ((1 - tx) * c0 + tx * c1) * float(nx_ - 1) * float(ny_ - 1)};
}

PiecewiseLinear2D::Result PiecewiseLinear2D::invert(Vec2 p, const float* param) const {
    const Slices s = slicesAt(param);
    const uint32_t n = uint32_t(nx_) * ny_;
    const Patch q = patchAt(p, nx_, ny_);
    const uint32_t col = q.col, row = q.row;
    const float fx = q.fx, fy = q.fy;

    const uint32_t at = row * nx_ + col;
    const auto [v00, v10, v01, v11] = cornersAt(s, at);
    float c0 = (1 - fy) * v00 + fy * v01, c1 = (1 - fy) * v10 + fy * v11;
    float pdf = (1 - fx) * c0 + fx * c1;

    // x: the conditional cdf at (fx, fy) over the row's integral at fy.
    float ux = fx * (c0 + 0.5f * fx * (c1 - c0));
    ux += (1 - fy) * lookup(conditional_, s, at, n) + fy * lookup(conditional_, s, at + nx_, n);
    const uint32_t rowStart = row * nx_;
    float r0 = lookup(conditional_, s, rowStart + nx_ - 1, n), r1 = lookup(conditional_, s, rowStart + 2 * nx_ - 1, n);
    ux /= (1 - fy) * r0 + fy * r1;
    // y: the marginal cdf at fy.
    float uy = fy * (r0 + 0.5f * fy * (r1 - r0)) + lookup(marginal_, s, row, ny_);
    return {Vec2(ux, uy), pdf * float(nx_ - 1) * float(ny_ - 1)};
}

float PiecewiseLinear2D::evaluate(Vec2 p, const float* param) const {
    const Slices s = slicesAt(param);
    const Patch q = patchAt(p, nx_, ny_);
    const uint32_t col = q.col, row = q.row;
    const float fx = q.fx, fy = q.fy;
    const uint32_t at = row * nx_ + col;
    const auto [v00, v10, v01, v11] = cornersAt(s, at);
    float v = (1 - fy) * ((1 - fx) * v00 + fx * v10) + fy * ((1 - fx) * v01 + fx * v11);
    return marginal_.empty() ? v : v * float(nx_ - 1) * float(ny_ - 1);
}

}  // namespace ps
