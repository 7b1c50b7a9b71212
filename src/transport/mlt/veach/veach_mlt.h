// Veach's Metropolis light transport (thesis ch. 11), `--integrator mlt`: a Markov chain
// over path space itself, whose state is a path of vertices (path_space.h) and whose target
// is the luminance of its measurement contribution f(x); the RGB contribution is splatted.
//
// With the chain machinery of the primary-sample-space variants:
//  - bootstrap: N BDPT samples (a light and a camera subpath, every path their joins make,
//    and through a thin lens the light subpath's lens crossings (t = 0), each weighted by f
//    over the sum of its strategies' densities: the balance heuristic)
//    estimate b = the integral of the target, and each chain starts from one of their paths
//    drawn in proportion to its weight (no start-up bias); the drawn sample is generated
//    again from its own random stream and must give the same weights, bit for bit;
//  - expected values: the state is splatted with weight 1 - a and the proposal with a, each
//    divided by its target value; the image is scaled by b / mutations;
//  - chains own their random streams and advance in passes, splats are summed in fixed
//    point, even and odd chains fill the film's two halves: the image does not depend on
//    the thread count, and a stopped render has mutations from every chain.
// Direct lighting apart (--mlt-direct N, as Veach did, thesis ch. 11): the paths of at most
// one bounce (two edges: emission seen directly, and direct lighting through any BSDF) are
// rendered first by the path tracer (next-event estimation with MIS) at N samples per pixel
// and added to the image; the bootstrap's b and the chains' target leave them out (a proposal
// of such a path has target 0 and is rejected). Off by default.
#pragma once
#include "transport/mlt/metropolis.h"
#include "transport/mlt/veach/mutator.h"

namespace ps {

class VeachMLTIntegrator final : public Integrator {
public:
    VeachMLTIntegrator(const Scene& scene, int maxDepth, const MetropolisParams& params,
                       const VeachMutations& mutations = {});
    // Not a per-ray estimator: render() runs renderVeachMLT instead.
    Spectrum Li(const Ray& ray, SampleContext& ctx) const override;
    bool splats() const override { return true; }
    bool supportsSpectral() const override { return true; }
    const char* name() const { return "mlt"; }

    const PathSpace& space() const { return space_; }
    const BidirectionalMutation& bidirectional() const { return bidirectional_; }
    const Perturbations& perturbations() const { return perturbations_; }
    const LensSubpathMutation& lensSubpath() const { return lensSubpath_; }
    const WavelengthMutation& wavelengths() const { return wavelengths_; }
    const Mutator& mutator() const { return mutator_; }
    const MetropolisParams& params() const { return params_; }
    const VeachMutations& mutations() const { return mutations_; }
    // Direct lighting apart: the path tracer's samples per pixel (0: off), and the fewest
    // vertices of a path the chains hold (4 with it: three edges, else 2).
    int directSpp() const { return int(mutations_.direct); }
    int minChainVertices() const { return directSpp() > 0 ? 4 : 2; }

private:
    PathSpace space_;
    BidirectionalMutation bidirectional_;
    LensSubpathMutation lensSubpath_;
    Perturbations perturbations_;
    WavelengthMutation wavelengths_;
    MetropolisParams params_;
    VeachMutations mutations_;
    Mutator mutator_;
};

// The Markov-chain driver: options.spp mutations per film pixel (crop region); threads,
// seed, time limit, cancellation and progress as for render().
// Throws InputError for what mlt does not render (before any work: every process alike).
void requireVeachMLTSupport(const Scene& scene, const VeachMLTIntegrator& integrator);
RenderResult renderVeachMLT(const Scene& scene, const VeachMLTIntegrator& integrator, const RenderOptions& options);

}  // namespace ps
