// Pixel reconstruction filters, used as pbrt-v4 does (PBRT-CONVENTIONS §1): each camera
// sample draws its offset from the filter and carries weight f/pdf, so a pixel is the mean
// of radiance over filter-distributed positions (no splatting of camera samples).
#pragma once
#include <memory>
#include <string>
#include "math/vec.h"
#include "mc/distribution.h"

namespace ps {

struct FilterSample {
    Vec2 offset;     // from the pixel centre, within the radius
    float weight;    // f(offset) / pdf(offset)
};

class Filter {
public:
    Filter(Vec2 radius) : radius_(radius) {}
    virtual ~Filter() = default;
    virtual float evaluate(Vec2 p) const = 0;
    virtual FilterSample sample(Vec2 u) const = 0;
    virtual float integral() const = 0;
    Vec2 radius() const { return radius_; }

protected:
    Vec2 radius_;
};

class BoxFilter final : public Filter {
public:
    using Filter::Filter;
    float evaluate(Vec2 p) const override {
        return std::fabs(p.x) <= radius_.x && std::fabs(p.y) <= radius_.y ? 1.0f : 0.0f;
    }
    FilterSample sample(Vec2 u) const override {
        return {{lerp(u.x, -radius_.x, radius_.x), lerp(u.y, -radius_.y, radius_.y)}, 1.0f};
    }
    float integral() const override { return 4 * radius_.x * radius_.y; }
};

class TriangleFilter final : public Filter {
public:
    using Filter::Filter;
    float evaluate(Vec2 p) const override {
        return std::max(0.0f, radius_.x - std::fabs(p.x)) * std::max(0.0f, radius_.y - std::fabs(p.y));
    }
    // Exact inversion of the separable tent: weight 1.
    FilterSample sample(Vec2 u) const override { return {{sampleTent(u.x, radius_.x), sampleTent(u.y, radius_.y)}, 1.0f}; }
    float integral() const override { return sqr(radius_.x) * sqr(radius_.y); }

private:
    static float sampleTent(float u, float r) {
        if (u < 0.5f) {
            float up = u * 2;
            return -r + r * std::sqrt(up);
        }
        float up = u * 2 - 1;
        return r - r * std::sqrt(1 - up);
    }
};

// Filters without a closed-form inverse: sampled from a table of |f| on a grid of 32
// cells per unit radius; weight = f/pdf.
class TabulatedFilter : public Filter {
public:
    using Filter::Filter;
    FilterSample sample(Vec2 u) const override;
    float integral() const override { return integral_; }

protected:
    void buildTable();  // call at the end of a derived constructor

private:
    Distribution2D distribution_;
    std::vector<float> table_;
    int nx_ = 0, ny_ = 0;
    float integral_ = 0;
};

class GaussianFilter final : public TabulatedFilter {
public:
    GaussianFilter(Vec2 radius, float sigma);
    float evaluate(Vec2 p) const override;

private:
    float gauss(float x) const;
    float sigma_, expX_, expY_;
};

class MitchellFilter final : public TabulatedFilter {
public:
    MitchellFilter(Vec2 radius, float b, float c);
    float evaluate(Vec2 p) const override;

private:
    float mitchell1D(float x) const;
    float b_, c_;
};

}  // namespace ps
