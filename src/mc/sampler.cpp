#include "mc/sampler.h"

#include "mc/halton_sampler.h"
#include "mc/orthogonal_array_sampler.h"
#include "mc/zsobol_sampler.h"

namespace ps {

SobolPermutationTable::SobolPermutationTable(int log2N, uint64_t seed) {
    const uint32_t n = 1u << log2N;
    entries.resize(size_t(kRows) * n * 2);
    for (uint32_t d = 0; d < kRows; ++d) {
        uint64_t key = mixWithKey(mix64(seed ^ 0x2545f4914f6cdd1dULL), d);
        for (uint32_t i = 0; i < n; ++i) {
            uint32_t p = permuteNested(i, log2N, key);
            entries[(size_t(d) * n + i) * 2] = uint16_t(p);
            entries[(size_t(d) * n + i) * 2 + 1] = uint16_t(sobolDim1Reversed(p));
        }
    }
}

uint32_t PaddedSobolSampler::permutationBlock(int samplesPerPixel) {
    const uint32_t n = uint32_t(samplesPerPixel < 1 ? 1 : samplesPerPixel);
    if ((n & (n - 1)) == 0 && n <= kLargestBlock) return n;
    if (n > SobolPermutationTable::kMaxSamples) return SobolPermutationTable::kMaxSamples;
    uint32_t block = 1;
    while (block < n) block *= 4;
    return block;
}

PaddedSobolSampler::PaddedSobolSampler(uint64_t seed, int samplesPerPixel)
    : seed_(seed), n_(permutationBlock(samplesPerPixel)), log2N_(__builtin_ctz(n_)) {
    if (SobolPermutationTable::covers(n_)) table_ = std::make_shared<const SobolPermutationTable>(log2N_, seed);
}

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
