#include "transport/mlt/mmlt.h"

#include <algorithm>
#include <cmath>

namespace ps {

MMLTIntegrator::MMLTIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params,
                               MisHeuristic heuristic)
    : MetropolisIntegrator(scene, maxDepth, params, heuristic) {
    // The chain chooses each subpath's length: roulette would only add zeros to the target.
    bdpt_.setRoulette(false);
}

void MMLTIntegrator::prepareBootstrap(PrimarySampleSampler& sampler, int64_t i) const {
    const int depths = maxDepth() + 1;
    sampler.stratify(kStrategyStream, 0, int(i % depths), depths);
}

void MMLTIntegrator::evaluate(PrimarySampleSampler& sampler, ChainEvaluator& ev, ChainState& out) const {
    out.splats.clear();
    out.f = 0;
    sampler.startStream(kStrategyStream);
    const int depths = maxDepth() + 1;
    const int depth = std::min(int(sampler.get1D() * float(depths)), depths - 1);
    // Depth 0 (an emitter seen directly) has one strategy: the camera ray finds it (its
    // BDPT weight is 1).
    const int strategies = depth == 0 ? 1 : depth + 2;
    const int s = depth == 0 ? 0 : std::min(int(sampler.get1D() * float(strategies)), strategies - 1);
    const int t = depth + 2 - s;
    out.depth = depth;

    CameraSample cs = filmSample(sampler);
    Ray ray = scene_.camera().generateRay(cs);
    BDPTIntegrator::PathContribution c;
    if (bdpt_.strategyContribution(ray, cs.pFilm, s, t, sampler, ev.scratch, ev.stats, c)) {
        c.L *= float(strategies) * float(depths);
        double f = c.L.luminance();
        if (std::isfinite(f) && f > 0) {
            out.f = f;
            out.splats.push_back(c);
        }
    }
    ev.scratch.reset();
}

}  // namespace ps
