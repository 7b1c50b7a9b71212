#include "mc/sampler.h"

namespace ps {

std::unique_ptr<Sampler> createSampler(const std::string& name, uint64_t seed, int samplesPerPixel) {
    if (name == "independent") return std::make_unique<IndependentSampler>(seed);
    if (name == "sobol") return std::make_unique<PaddedSobolSampler>(seed, samplesPerPixel);
    if (name == "stratified") return std::make_unique<StratifiedSampler>(seed, samplesPerPixel, false);
    if (name == "lhs") return std::make_unique<StratifiedSampler>(seed, samplesPerPixel, true);
    return nullptr;
}

}  // namespace ps
