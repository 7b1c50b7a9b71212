#include "mc/distribution.h"

#include <algorithm>
#include <cmath>

namespace ps {

Distribution1D::Distribution1D(std::span<const float> weights) {
    size_t n = std::max<size_t>(1, weights.size());
    func_.assign(n, 0.0f);
    for (size_t i = 0; i < weights.size(); ++i)
        func_[i] = (std::isfinite(weights[i]) && weights[i] > 0) ? weights[i] : 0.0f;
    cdf_.assign(n + 1, 0.0f);
    double sum = 0;
    for (float f : func_) sum += f;
    if (!(sum > 0)) {
        std::fill(func_.begin(), func_.end(), 1.0f);
        sum = double(n);
    }
    integral_ = float(sum / double(n));
    double acc = 0;
    for (size_t i = 0; i < n; ++i) {
        acc += func_[i];
        cdf_[i + 1] = float(acc / sum);
    }
    cdf_[n] = 1.0f;
}

static int findInterval(const std::vector<float>& cdf, float u) {
    // Largest i with cdf[i] <= u, clamped to a valid bin. Small tables (a few lights) by
    // counting without early exit: no branch to mispredict on a random u.
    if (cdf.size() <= 17) {
        int count = 0;
        for (size_t i = 1; i + 1 < cdf.size(); ++i) count += cdf[i] <= u;
        return count;
    }
    auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    int i = int(it - cdf.begin()) - 1;
    return std::clamp(i, 0, int(cdf.size()) - 2);
}

float Distribution1D::sampleContinuous(float u, float* pdf, int* offset) const {
    int i = findInterval(cdf_, u);
    // Skip zero-probability bins that upper_bound may land on at their boundary.
    while (i + 1 < size() && cdf_[i + 1] <= u) ++i;
    if (offset) *offset = i;
    float du = u - cdf_[i];
    float width = cdf_[i + 1] - cdf_[i];
    if (width > 0) du /= width;
    if (pdf) *pdf = integral_ > 0 ? func_[i] / integral_ : 0.0f;
    float x = (float(i) + du) / float(size());
    return std::min(x, 0x1.fffffep-1f);
}

int Distribution1D::sampleDiscrete(float u, float* pmfOut, float* uRemapped) const {
    int i = findInterval(cdf_, u);
    while (i + 1 < size() && cdf_[i + 1] <= u) ++i;
    float width = cdf_[i + 1] - cdf_[i];
    if (pmfOut) *pmfOut = width;
    if (uRemapped) *uRemapped = width > 0 ? std::min((u - cdf_[i]) / width, 0x1.fffffep-1f) : 0.0f;
    return i;
}

float Distribution1D::pdf(float x) const {
    int i = std::clamp(int(x * float(size())), 0, size() - 1);
    return integral_ > 0 ? func_[i] / integral_ : 0.0f;
}

Distribution2D::Distribution2D(std::span<const float> weights, int nu, int nv) {
    conditional_.reserve(nv);
    std::vector<float> rowIntegrals(nv);
    for (int v = 0; v < nv; ++v) {
        conditional_.emplace_back(weights.subspan(size_t(v) * nu, nu));
        // A row that was all zero reports a uniform integral; its true weight is 0.
        double s = 0;
        for (int u = 0; u < nu; ++u) {
            float w = weights[size_t(v) * nu + u];
            if (std::isfinite(w) && w > 0) s += w;
        }
        rowIntegrals[v] = float(s / nu);
    }
    marginal_ = Distribution1D(rowIntegrals);
}

Vec2 Distribution2D::sampleContinuous(Vec2 u, float* pdf) const {
    float pdfs[2];
    int v;
    float d1 = marginal_.sampleContinuous(u.y, &pdfs[1], &v);
    float d0 = conditional_[v].sampleContinuous(u.x, &pdfs[0]);
    *pdf = pdfs[0] * pdfs[1];
    return {d0, d1};
}

float Distribution2D::pdf(Vec2 p) const {
    int nv = int(conditional_.size());
    int v = std::clamp(int(p.y * float(nv)), 0, nv - 1);
    return conditional_[v].pdf(p.x) * marginal_.pdf(p.y);
}

}  // namespace ps
