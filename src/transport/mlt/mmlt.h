// Multiplexed Metropolis light transport (Hachisuka et al. 2014) over BDPT: the chain's
// state also chooses the path depth and one (s, t) strategy of that depth, and the target
// is the luminance of that strategy's MIS-weighted contribution times the number of ways
// to choose it (strategies of its depth times depths). A sample then costs one connection
// and subpaths of exactly the lengths it needs, and the chain spends its time on the
// strategies that carry the light.
//
// The depth is a coordinate of the chain (its own dimension, perturbed by small steps and
// redrawn by large ones), not fixed per chain: the chains move between depths, so each
// depth's share of the image converges to its true value as the render goes on, whatever
// the bootstrap estimated. Fixing the depth per chain instead freezes each depth's share
// at the bootstrap's estimate (the chains are split between depths once), a bias in the
// image's balance that no number of mutations removes.
#pragma once
#include "transport/mlt/metropolis.h"

namespace ps {

class MMLTIntegrator final : public MetropolisIntegrator {
public:
    MMLTIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params = {},
                   MisHeuristic heuristic = MisHeuristic::Power);
    const char* name() const override { return "mmlt"; }
    void evaluate(PrimarySampleSampler& sampler, ChainEvaluator& ev, ChainState& out) const override;
    // The depth and strategy are drawn from a stream of their own.
    static constexpr int kStrategyStream = BDPTIntegrator::kStreamCount;
    int streamCount() const override { return BDPTIntegrator::kStreamCount + 1; }
    // As the bootstrap of a chain per depth would: the parameter's count per depth.
    int64_t bootstrapCount() const override { return int64_t(params_.bootstrapSamples) * (maxDepth() + 1); }
    bool choosesDepth() const override { return true; }
    // The bootstrap takes each depth equally often (sample i has depth i mod depths), as
    // many samples per depth as the parameter says: b's error then has no part from the
    // random choice of depths, whose images differ by orders of magnitude.
    void prepareBootstrap(PrimarySampleSampler& sampler, int64_t i) const override;
};

}  // namespace ps
