#include "mc/sampler.h"

namespace ps {

std::unique_ptr<Sampler> createSampler(const std::string& name, uint64_t seed) {
    if (name == "independent") return std::make_unique<IndependentSampler>(seed);
    if (name == "sobol") return std::make_unique<PaddedSobolSampler>(seed);
    return nullptr;
}

}  // namespace ps
