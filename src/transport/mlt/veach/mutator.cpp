#include "transport/mlt/veach/mutator.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "util/error.h"

namespace ps {

const char* mutationName(Mutation m) {
    switch (m) {
        case Mutation::Bidirectional: return "bidirectional";
        case Mutation::LensSubpath: return "lens subpath";
        case Mutation::Lens: return "lens perturbation";
        case Mutation::MultiChain: return "multi-chain perturbation";
        case Mutation::Caustic: return "caustic perturbation";
        case Mutation::Wavelengths: return "wavelengths";
        case Mutation::Regenerate: return "regenerate";
        case Mutation::Count: break;
    }
    return "?";
}

double VeachMutations::weight(Mutation m) const {
    if (regenerate) return m == Mutation::Regenerate ? 1.0 : 0.0;
    switch (m) {
        case Mutation::Bidirectional: return bidirectional;
        case Mutation::LensSubpath: return lensSubpath;
        case Mutation::Lens: return lens;
        case Mutation::MultiChain: return multiChain;
        case Mutation::Caustic: return caustic;
        case Mutation::Wavelengths: return wavelengths;
        default: return 0;
    }
}

VeachMutations parseMutationWeights(const std::string& spec) {
    VeachMutations w;
    std::stringstream in(spec);
    std::string item;
    while (std::getline(in, item, ',')) {
        if (item.empty()) continue;
        const size_t eq = item.find('=');
        const std::string key = item.substr(0, eq);
        double* target = key == "bidirectional"  ? &w.bidirectional
                         : key == "lens-subpath" ? &w.lensSubpath
                         : key == "lens"         ? &w.lens
                         : key == "multi-chain"  ? &w.multiChain
                         : key == "caustic"      ? &w.caustic
                         : key == "wavelengths"  ? &w.wavelengths
                         : key == "direct"       ? &w.direct
                                                 : nullptr;
        if (!target)
            throw InputError("--mlt-mutations: unknown mutation \"" + key +
                             "\" (available: bidirectional, lens-subpath, lens, multi-chain, caustic, wavelengths; and "
                             "direct)");
        const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
        char* end = nullptr;
        const double v = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0' || !(v >= 0) || !std::isfinite(v))
            throw InputError("--mlt-mutations: \"" + item + "\" needs a weight >= 0, as in " + key + "=0.5");
        if (target == &w.direct && v != std::floor(v))
            throw InputError("--mlt-direct: \"" + value + "\" needs a whole number of samples per pixel");
        *target = v;
    }
    if (!(w.bidirectional > 0))
        throw InputError("--mlt-mutations: the bidirectional mutation needs a weight > 0 (the other mutations keep a "
                         "path's length and specular structure, so alone they cannot reach every path)");
    return w;
}

bool Mutator::applies(Mutation m, const MltPath& x) const {
    if (!(weights_.weight(m) > 0)) return false;
    switch (m) {
        case Mutation::LensSubpath: return lensSubpath_.applies(x);
        case Mutation::Lens: return perturbations_.lensApplies(x);
        case Mutation::MultiChain: return perturbations_.multiChainApplies(x);
        case Mutation::Caustic: return perturbations_.causticApplies(x);
        case Mutation::Wavelengths: return wavelengths_.applies(x);
        default: return true;
    }
}

double Mutator::applicableWeight(const MltPath& x) const {
    double sum = 0;
    for (int k = 0; k < int(Mutation::Count); ++k)
        if (applies(Mutation(k), x)) sum += weights_.weight(Mutation(k));
    return sum;
}

double Mutator::probability(Mutation m, const MltPath& x) const {
    return applies(m, x) ? weights_.weight(m) / applicableWeight(x) : 0.0;
}

bool Mutator::mutate(const MltPath& x, Vec2 rasterX, Rng& rng, ScratchBuffer& arena,
                     PathStats& stats, MltPath& y, Mutation* chosen, double* ratio) const {
    const double sum = applicableWeight(x);
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
        case Mutation::LensSubpath: made = lensSubpath_.propose(x, rng, arena, stats, y, &r); break;
        case Mutation::Lens:
        case Mutation::MultiChain: made = perturbations_.lens(x, rasterX, rng, arena, stats, y, &r); break;
        case Mutation::Caustic: made = perturbations_.caustic(x, rng, arena, stats, y, &r); break;
        case Mutation::Wavelengths: made = wavelengths_.propose(x, rng, arena, y, &r); break;
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
    *ratio = r * probability(m, y) / (weights_.weight(m) / sum);
    return true;
}

}  // namespace ps
