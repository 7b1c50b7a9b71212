// Primary-sample-space Metropolis light transport over BDPT (Kelemen et al. 2002): Markov
// chains over the random numbers of one BDPT sample, whose target is the luminance of that
// sample's whole MIS-weighted contribution (every strategy of one camera and one light
// subpath). Each strategy's share is splatted at its own film position.
#pragma once
#include "transport/mlt/metropolis.h"

namespace ps {

class PSSMLTIntegrator final : public MetropolisIntegrator {
public:
    PSSMLTIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params = {},
                     MisWeighting mis = {})
        : MetropolisIntegrator(scene, maxDepth, params, mis) {}
    const char* name() const override { return "pssmlt"; }
    void evaluate(PrimarySampleSampler& sampler, const StrategyChoice& choice, ChainEvaluator& ev,
                  ChainState& out) const override;
};

}  // namespace ps
