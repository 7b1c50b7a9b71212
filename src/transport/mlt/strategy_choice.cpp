#include "transport/mlt/strategy_choice.h"

#include <span>

namespace ps {

StrategyChoice::StrategyChoice(const std::vector<float>& weights, const std::vector<int>& groupStart)
    : weights_(weights), groupStart_(groupStart) {
    const int groups = int(groupStart_.size());
    std::vector<float> groupWeights(size_t(groups), 0.0f);
    for (int g = 0; g < groups; ++g) {
        const int begin = groupStart_[size_t(g)];
        const int end = g + 1 < groups ? groupStart_[size_t(g) + 1] : int(weights_.size());
        std::span<const float> w(weights_.data() + begin, size_t(end - begin));
        within_.emplace_back(w);
        double sum = 0;
        for (float x : w) sum += x > 0 ? x : 0;
        groupWeights[size_t(g)] = float(sum);
        for (int k = begin; k < end; ++k) groupOf_.push_back(g);
    }
    groups_ = Distribution1D(groupWeights);
}

float StrategyChoice::pmf(int k) const {
    const int g = groupOf_[size_t(k)];
    return groups_.pmf(g) * within_[size_t(g)].pmf(k - groupStart_[size_t(g)]);
}

int StrategyChoice::sample(float u1, float u2, float* pmfOut) const {
    const int g = groups_.sampleDiscrete(u1);
    const int k = groupStart_[size_t(g)] + within_[size_t(g)].sampleDiscrete(u2);
    if (pmfOut) *pmfOut = pmf(k);
    return k;
}

namespace {
// A value at u within bin i of d that still falls in bin i once read as a float.
double inBin(const Distribution1D& d, int i, double u) {
    double v = double(d.cdf(i)) + u * double(d.pmf(i));
    return d.sampleDiscrete(float(v)) == i ? v : double(d.cdf(i));
}
}  // namespace

void StrategyChoice::place(int k, double u1, double u2, double& v1, double& v2) const {
    const int g = groupOf_[size_t(k)];
    v1 = inBin(groups_, g, u1);
    v2 = inBin(within_[size_t(g)], k - groupStart_[size_t(g)], u2);
}

}  // namespace ps
