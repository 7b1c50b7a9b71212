#include "film/filter.h"

#include <cmath>

namespace ps {

void TabulatedFilter::buildTable() {
    nx_ = std::max(1, int(32 * radius_.x));
    ny_ = std::max(1, int(32 * radius_.y));
    table_.resize(size_t(nx_) * ny_);
    double sum = 0;
    for (int y = 0; y < ny_; ++y)
        for (int x = 0; x < nx_; ++x) {
            Vec2 p(lerp((x + 0.5f) / nx_, -radius_.x, radius_.x), lerp((y + 0.5f) / ny_, -radius_.y, radius_.y));
            float f = evaluate(p);
            table_[size_t(y) * nx_ + x] = std::fabs(f);
            sum += f;
        }
    integral_ = float(sum * (4.0 * radius_.x * radius_.y) / (double(nx_) * ny_));
    distribution_ = Distribution2D(table_, nx_, ny_);
}

FilterSample TabulatedFilter::sample(Vec2 u) const {
    float pdfUnit;
    Vec2 s = distribution_.sampleContinuous(u, &pdfUnit);
    Vec2 p(lerp(s.x, -radius_.x, radius_.x), lerp(s.y, -radius_.y, radius_.y));
    float pdf = pdfUnit / (4 * radius_.x * radius_.y);
    return {p, pdf > 0 ? evaluate(p) / pdf : 0.0f};
}

GaussianFilter::GaussianFilter(Vec2 radius, float sigma) : TabulatedFilter(radius), sigma_(sigma) {
    expX_ = gauss(radius.x);
    expY_ = gauss(radius.y);
    buildTable();
}

float GaussianFilter::gauss(float x) const {
    return std::exp(-x * x / (2 * sigma_ * sigma_)) / std::sqrt(2 * kPi * sigma_ * sigma_);
}

float GaussianFilter::evaluate(Vec2 p) const {
    return std::max(0.0f, gauss(p.x) - expX_) * std::max(0.0f, gauss(p.y) - expY_);
}

MitchellFilter::MitchellFilter(Vec2 radius, float b, float c) : TabulatedFilter(radius), b_(b), c_(c) { buildTable(); }

float MitchellFilter::mitchell1D(float x) const {
    x = std::fabs(x);
    float b = b_, c = c_;
    if (x <= 1)
        return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) * (1.f / 6.f);
    if (x <= 2)
        return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) *
               (1.f / 6.f);
    return 0;
}

float MitchellFilter::evaluate(Vec2 p) const {
    return mitchell1D(2 * p.x / radius_.x) * mitchell1D(2 * p.y / radius_.y);
}

}  // namespace ps
