// The choice among Veach's mutations (thesis §11.4): each with a fixed weight, normalised over
// the mutations that apply to the current path. Which apply depends on the path (a lens
// perturbation needs a (D|L) S* E ending), so the probability of the choice is part of T:
// a proposal's T(y -> x) / T(x -> y) includes P(mutation | y) / P(mutation | x).
#pragma once
#include "transport/mlt/veach/bidirectional_mutation.h"
#include "transport/mlt/veach/lens_subpath_mutation.h"
#include "transport/mlt/veach/perturbations.h"
#include "transport/mlt/veach/wavelength_mutation.h"

namespace ps {

enum class Mutation : int { Bidirectional, LensSubpath, Lens, MultiChain, Caustic, Wavelengths, Regenerate, Count };
const char* mutationName(Mutation m);

// The mutations' weights (over those that apply).
struct VeachMutations {
    // `wavelengths` applies in spectral mode only.
    // The wavelength mutation moves the colour alone (the lens and caustic perturbations move
    // the wavelengths too): at a quarter of the others' weight, the path's own mutations get
    // more of the proposals (bench/README, "In spectral mode").
    double bidirectional = 1, lensSubpath = 1, lens = 1, multiChain = 1, caustic = 1, wavelengths = 0.25;
    // For tests: only an independent path generated from nothing (T(x -> y) = its
    // generation density): the image must be BDPT's whatever the other mutations'
    // densities are, a check of the chain's bookkeeping alone.
    bool regenerate = false;
    // Not a mutation: the path tracer's samples per pixel for the paths of at most one
    // bounce, rendered apart from the chains (veach_mlt.h; key "direct", --mlt-direct N;
    // 0: the chains render them).
    double direct = 0;
    double weight(Mutation m) const;
};

// Weights from "KEY=VALUE,..." (keys bidirectional, lens-subpath, lens, multi-chain, caustic,
// wavelengths; values >= 0; unnamed keys keep their defaults; and direct=N, whole);
// InputError on anything else. The
// bidirectional mutation must keep a positive weight: the others alone cannot reach every
// path (they keep a path's length and specular structure).
VeachMutations parseMutationWeights(const std::string& spec);

class Mutator {
public:
    Mutator(const BidirectionalMutation& bidirectional, const LensSubpathMutation& lensSubpath,
            const Perturbations& perturbations, const WavelengthMutation& wavelengths, const VeachMutations& weights)
        : bidirectional_(bidirectional),
          lensSubpath_(lensSubpath),
          perturbations_(perturbations),
          wavelengths_(wavelengths),
          weights_(weights) {}
    bool applies(Mutation m, const MltPath& x) const;
    // Probability of choosing m at x (0 where it does not apply).
    double probability(Mutation m, const MltPath& x) const;
    // Chooses a mutation for x (whose contribution lands at rasterX) and proposes y; *ratio
    // receives T(y -> x) / T(x -> y), the choice included. False when the proposal failed
    // (the chain stays at x); *chosen is set either way.
    bool mutate(const MltPath& x, Vec2 rasterX, Rng& rng, ScratchBuffer& arena,
                PathStats& stats, MltPath& y, Mutation* chosen, double* ratio) const;

private:
    // The sum of the weights of the mutations that apply to x.
    double applicableWeight(const MltPath& x) const;

    const BidirectionalMutation& bidirectional_;
    const LensSubpathMutation& lensSubpath_;
    const Perturbations& perturbations_;
    const WavelengthMutation& wavelengths_;
    VeachMutations weights_;
};

}  // namespace ps
