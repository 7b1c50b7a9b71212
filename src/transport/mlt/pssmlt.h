// Primary-sample-space Metropolis light transport over BDPT (Kelemen et al. 2002; thesis
// ch. 11 for the chain's bookkeeping): Markov chains over the random numbers of one BDPT
// sample, whose target is the luminance of that sample's whole MIS-weighted contribution
// (every strategy of one camera and one light subpath). Each strategy's share is splatted
// at its own film position.
//
// A chain is not a per-camera-ray estimate, so this integrator has its own driver,
// renderMetropolis, which render() hands it to:
//  - bootstrap: N independent samples estimate b, the integral of the target over primary
//    sample space, and the chains' initial states are drawn from them in proportion to
//    their target values (no start-up bias, thesis ch. 11); each drawn state is replayed and
//    must reproduce its bootstrap value bit for bit;
//  - expected values: every iteration splats the current state with weight 1 - a and the
//    proposal with weight a, each contribution divided by its sample's target value;
//  - the image is scaled by b / (mutations made per film pixel), so an interrupted render
//    is normalised by the mutations it made;
//  - each chain owns its random streams (keyed by the seed and its index) and a fixed share
//    of the mutations, and splats accumulate in fixed point: the image does not depend on
//    the thread count;
//  - the chains' even and odd halves fill the film's two half-buffers, whose difference
//    gives the error estimate (independent chains, unlike the correlated samples of one).
#pragma once
#include <cstdint>
#include "transport/bdpt.h"
#include "transport/integrator.h"
#include "transport/renderer.h"

namespace ps {

struct MetropolisParams {
    int bootstrapSamples = 100000;
    int chains = 1000;
    double largeStepProbability = 0.3;
    double sigma = 0.01;
};

class PSSMLTIntegrator final : public Integrator {
public:
    PSSMLTIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params = {},
                     MisHeuristic heuristic = MisHeuristic::Power)
        : bdpt_(scene, maxDepth, heuristic), params_(params) {}
    // Not a per-ray estimator: render() runs renderMetropolis instead.
    Spectrum Li(const Ray& ray, SampleContext& ctx) const override;
    bool splats() const override { return true; }
    const BDPTIntegrator& bdpt() const { return bdpt_; }
    const MetropolisParams& params() const { return params_; }
    MetropolisParams& params() { return params_; }

private:
    BDPTIntegrator bdpt_;
    MetropolisParams params_;
};

// The Markov-chain driver: options.spp is the number of mutations per film pixel (crop
// region); threads, seed, time limit, cancellation and progress as for render().
RenderResult renderMetropolis(const Scene& scene, const PSSMLTIntegrator& integrator, const RenderOptions& options);

}  // namespace ps
