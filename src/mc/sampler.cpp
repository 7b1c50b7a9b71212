#include "mc/sampler.h"

#include "mc/halton_sampler.h"
#include "mc/orthogonal_array_sampler.h"
#include "mc/zsobol_sampler.h"

namespace ps {

std::unique_ptr<Sampler> createSampler(const std::string& name, uint64_t seed, int samplesPerPixel, int resolution) {
    if (name == "independent") return std::make_unique<IndependentSampler>(seed);
    if (name == "sobol") return std::make_unique<PaddedSobolSampler>(seed, samplesPerPixel);
    if (name == "stratified") return std::make_unique<StratifiedSampler>(seed, samplesPerPixel, false);
    if (name == "lhs") return std::make_unique<StratifiedSampler>(seed, samplesPerPixel, true);
    if (name == "orthogonal") return std::make_unique<OrthogonalArraySampler>(seed, samplesPerPixel);
    if (name == "halton") return std::make_unique<HaltonSampler>(seed, samplesPerPixel);
    if (name == "zsobol") return std::make_unique<ZSobolSampler>(seed, samplesPerPixel, resolution);
    return nullptr;
}

}  // namespace ps
