// Tabulated piecewise-constant densities sampled by inversion (thesis §2.4.1):
// 1-D over [0,1), and 2-D as a marginal over rows times conditionals within a row.
#pragma once
#include <span>
#include <vector>
#include "math/vec.h"

namespace ps {

class Distribution1D {
public:
    Distribution1D() = default;
    // Negative or non-finite weights count as 0; an all-zero table becomes uniform.
    explicit Distribution1D(std::span<const float> weights);

    int size() const { return int(func_.size()); }
    float integral() const { return integral_; }
    // Continuous sample in [0,1); pdf is the density with respect to [0,1); offset the bin.
    float sampleContinuous(float u, float* pdf, int* offset = nullptr) const;
    // Discrete sample: bin index with probability weight/sum.
    int sampleDiscrete(float u, float* pmf = nullptr, float* uRemapped = nullptr) const;
    float pmf(int i) const { return cdf_[i + 1] - cdf_[i]; }
    // Where bin i starts in [0,1): sampleDiscrete(u) is i for u in [cdf(i), cdf(i + 1)).
    float cdf(int i) const { return cdf_[i]; }
    // Density at x in [0,1).
    float pdf(float x) const;

private:
    std::vector<float> func_, cdf_;
    float integral_ = 0;
};

class Distribution2D {
public:
    Distribution2D() = default;
    // weights[v * nu + u], row v, column u.
    Distribution2D(std::span<const float> weights, int nu, int nv);
    // Sample (u, v) in [0,1)^2 with density pdf over the unit square.
    Vec2 sampleContinuous(Vec2 u, float* pdf) const;
    float pdf(Vec2 p) const;
    float integral() const { return marginal_.integral(); }

private:
    std::vector<Distribution1D> conditional_;
    Distribution1D marginal_;
};

}  // namespace ps
