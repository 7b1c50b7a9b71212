#include "transport/mlt/pssmlt.h"

#include <cmath>

namespace ps {

// The target is the luminance of the sum of every strategy's contribution.
void PSSMLTIntegrator::evaluate(PrimarySampleSampler& sampler, const StrategyChoice&, ChainEvaluator& ev,
                                ChainState& out) const {
    CameraSample cs = filmSample(sampler);
    SampledWavelengths* lambda = wavelengths(sampler, ev);
    Ray ray = scene_.camera().generateRay(cs);
    bdpt_.contributions(ray, cs.pFilm, sampler, ev.scratch, ev.stats, out.splats, -1, lambda);
    ev.scratch.reset();
    double f = 0;
    for (BDPTIntegrator::PathContribution& c : out.splats) {
        c.L = toRendering(c, ev);
        f += c.L.luminance();
    }
    out.f = std::isfinite(f) ? f : 0.0;
    out.depth = -1;
}

}  // namespace ps
