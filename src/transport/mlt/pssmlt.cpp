#include "transport/mlt/pssmlt.h"

#include <cmath>

namespace ps {

// The target is the luminance of the sum of every strategy's contribution (two-stage MLT:
// each over the pilot's brightness where it lands).
void PSSMLTIntegrator::evaluate(PrimarySampleSampler& sampler, const StrategyChoice&, ChainEvaluator& ev,
                                ChainState& out) const {
    bdptSample(sampler, ev, out.splats);
    double f = 0;
    for (const BDPTIntegrator::PathContribution& c : out.splats) f += c.L.luminance() / ev.brightness(c.pRaster);
    out.f = std::isfinite(f) ? f : 0.0;
    out.depth = -1;
}

}  // namespace ps
