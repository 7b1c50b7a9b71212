// Multiplexed Metropolis light transport (Hachisuka et al. 2014) over BDPT: the chain's
// state also chooses the path depth and one (s, t) strategy of that depth, and the target
// is the luminance of that strategy's MIS-weighted contribution divided by the probability
// of choosing it. A sample then costs one connection and subpaths of exactly the lengths
// it needs, and the chain spends its time on the strategies that carry the light.
//
// The depth is a coordinate of the chain (part of the choice, perturbed by small steps and
// redrawn by large ones), not fixed per chain: the chains move between depths, so each
// depth's share of the image converges to its true value as the render goes on, whatever
// the bootstrap estimated. Fixing the depth per chain instead freezes each depth's share
// at the bootstrap's estimate (the chains are split between depths once), a bias in the
// image's balance that no number of mutations removes.
//
// How often the choice picks each (depth, s) pair does not change what the chain converges
// to (the target's marginal over the pairs is each pair's share of the image, whatever the
// probabilities), only how well large steps and the bootstrap sample it: the driver learns
// probabilities close to those shares from a pilot (bootstrap.h), where the default
// (each depth equally, then each of its strategies equally) wastes most large steps on
// depths and strategies that carry almost nothing.
#pragma once
#include <algorithm>
#include <utility>
#include <vector>
#include "transport/mlt/metropolis.h"

namespace ps {

class MMLTIntegrator final : public MetropolisIntegrator {
public:
    MMLTIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params = {},
                   MisWeighting mis = {});
    const char* name() const override { return "mmlt"; }
    void evaluate(PrimarySampleSampler& sampler, const StrategyChoice& choice, ChainEvaluator& ev,
                  ChainState& out) const override;
    // Each depth equally, then each strategy of that depth equally.
    StrategyChoice defaultChoice() const override;
    // The (depth, s) pair of each strategy index, depth-major.
    const std::vector<std::pair<int, int>>& strategies() const { return strategies_; }
    // The depth and strategy are drawn from a stream of their own.
    static constexpr int kStrategyStream = BDPTIntegrator::kStreamCount;
    int streamCount() const override { return BDPTIntegrator::kStreamCount + 1; }
    // As the bootstrap of a chain per depth would: the parameter's count per depth, up to
    // kBootstrapDepths depths; past them the same total is shared by all (the pilot's
    // allocation gives most to the depths that carry the image). pbrt-v4 takes the count
    // per depth at any depth: 10^8 paths at maxdepth 1000, out of memory and hours long.
    static constexpr int kBootstrapDepths = 16;
    int64_t bootstrapCount() const override {
        return int64_t(params_.bootstrapSamples) * std::min(maxDepth() + 1, kBootstrapDepths);
    }
    bool choosesDepth() const override { return true; }
    PartialStepKind partialStepKind(const ChainState& x) const override;
    // A bootstrap sample of a depth stands for every strategy of that depth, from one
    // camera and one light subpath just long enough: b's estimate is then BDPT's for that
    // depth, not one strategy's. Each state is weighted by scale times its luminance,
    // whatever the choice's probabilities.
    int bootstrapGroups() const override { return maxDepth() + 1; }
    // Rays per sample: about d + 2 camera, d + 1 light and d + 2 connection rays.
    double groupCost(int depth) const override { return 3.0 * depth + 5; }
    void bootstrapSample(PrimarySampleSampler& sampler, int depth, double scale, const StrategyChoice& choice,
                         ChainEvaluator& ev, std::vector<BootstrapState>& out) const override;
    void chooseStrategy(PrimarySampleSampler& sampler, int strategy, const StrategyChoice& choice, double u1,
                        double u2) const override;

private:
    std::vector<std::pair<int, int>> strategies_;
    std::vector<int> firstOfDepth_;  // the index of (depth, s = 0)
};

}  // namespace ps
