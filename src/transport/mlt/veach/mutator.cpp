#include "transport/mlt/veach/mutator.h"

#include <cmath>

namespace ps {

const char* mutationName(Mutation m) {
    switch (m) {
        case Mutation::Bidirectional: return "bidirectional";
        case Mutation::Lens: return "lens perturbation";
        case Mutation::MultiChain: return "multi-chain perturbation";
        case Mutation::Caustic: return "caustic perturbation";
        case Mutation::Regenerate: return "regenerate";
        case Mutation::Count: break;
    }
    return "?";
}

double VeachMutations::weight(Mutation m) const {
    if (regenerate) return m == Mutation::Regenerate ? 1.0 : 0.0;
    switch (m) {
        case Mutation::Bidirectional: return bidirectional;
        case Mutation::Lens: return lens;
        case Mutation::MultiChain: return multiChain;
        case Mutation::Caustic: return caustic;
        default: return 0;
    }
}

bool Mutator::applies(Mutation m, const MltPath& x) const {
    if (!(weights_.weight(m) > 0)) return false;
    switch (m) {
        case Mutation::Lens: return perturbations_.lensApplies(x);
        case Mutation::MultiChain: return perturbations_.multiChainApplies(x);
        case Mutation::Caustic: return perturbations_.causticApplies(x);
        default: return true;
    }
}

double Mutator::probability(Mutation m, const MltPath& x) const {
    if (!applies(m, x)) return 0;
    double sum = 0;
    for (int k = 0; k < int(Mutation::Count); ++k)
        if (applies(Mutation(k), x)) sum += weights_.weight(Mutation(k));
    return weights_.weight(m) / sum;
}

bool Mutator::mutate(const MltPath& x, Vec2 rasterX, Rng& rng, ScratchBuffer& arena, PathStats& stats, MltPath& y,
                     Mutation* chosen, double* ratio) const {
    double sum = 0;
    for (int k = 0; k < int(Mutation::Count); ++k)
        if (applies(Mutation(k), x)) sum += weights_.weight(Mutation(k));
    double u = rng.uniformDouble() * sum;
    Mutation m = Mutation::Count;
    for (int k = 0; k < int(Mutation::Count); ++k)
        if (applies(Mutation(k), x)) {
            m = Mutation(k);
            if ((u -= weights_.weight(m)) < 0) break;
        }
    *chosen = m;
    double r = 0;
    bool made = false;
    switch (m) {
        case Mutation::Bidirectional: {
            double Txy = 0, Tyx = 0;
            made = bidirectional_.propose(x, rng, arena, stats, y, &Txy, &Tyx) && Txy > 0;
            r = made ? Tyx / Txy : 0.0;
            break;
        }
        case Mutation::Lens:
        case Mutation::MultiChain: made = perturbations_.lens(x, rasterX, rng, arena, stats, y, &r); break;
        case Mutation::Caustic: made = perturbations_.caustic(x, rng, arena, stats, y, &r); break;
        case Mutation::Regenerate: {
            double py = 0;
            made = bidirectional_.generate(rng, arena, stats, y, &py) && py > 0;
            r = made ? bidirectional_.generationDensity(x) / py : 0.0;
            break;
        }
        case Mutation::Count: return false;
    }
    if (!made) return false;
    // The choice itself: made at x forwards, at y for the way back.
    *ratio = r * probability(m, y) / probability(m, x);
    return true;
}

}  // namespace ps
