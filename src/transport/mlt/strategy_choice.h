// The discrete choice a multiplexed Metropolis target makes among its strategies: groups
// (path depths) and the strategies of each, chosen by inversion from two primary-sample
// values, a group from the first and a strategy of the group from the second. A small step
// of either value then changes the choice only near a boundary of its interval, as wide as
// the choice's probability, so small steps mostly keep the depth and the strategy (a
// single value over all strategies would have intervals a few times sigma wide).
#pragma once
#include <vector>
#include "mc/distribution.h"

namespace ps {

class StrategyChoice {
public:
    StrategyChoice() = default;
    // weights[k] of strategy k; group g holds strategies groupStart[g] .. groupStart[g+1]-1.
    StrategyChoice(const std::vector<float>& weights, const std::vector<int>& groupStart);
    // The same groups with other weights.
    StrategyChoice withWeights(const std::vector<float>& weights) const { return {weights, groupStart_}; }

    int size() const { return int(groupOf_.size()); }
    bool empty() const { return groupOf_.empty(); }
    const std::vector<float>& weights() const { return weights_; }
    // The probability of strategy k, as sample() reports it.
    float pmf(int k) const;
    int groupOf(int k) const { return groupOf_[size_t(k)]; }
    int groups() const { return int(groupStart_.size()); }
    // The strategies of group g: groupBegin(g) .. groupBegin(g + 1) - 1 (g = groups(): size()).
    int groupBegin(int g) const { return g < groups() ? groupStart_[size_t(g)] : size(); }
    // Strategy from two values in [0,1), and its probability.
    int sample(float u1, float u2, float* pmf) const;
    // Values (u1, u2) that choose strategy k: each at u (in [0,1)) within its interval.
    void place(int k, double u1, double u2, double& v1, double& v2) const;

private:
    std::vector<float> weights_;
    std::vector<int> groupStart_, groupOf_;
    Distribution1D groups_;
    std::vector<Distribution1D> within_;
};

}  // namespace ps
