// Randomised Halton points per pixel: sample i of a pixel takes, in dimension d, the
// radical inverse of i in the d-th prime base, Owen-scrambled with a seed per (pixel,
// dimension). The first b^k samples are stratified in b^k intervals in every dimension of base
// b, and the scrambling decorrelates pixels and removes the correlation between the large
// bases that plain Halton points show.
#pragma once
#include "mc/radical_inverse.h"
#include "mc/sampler.h"

namespace ps {

class HaltonSampler final : public Sampler {
public:
    HaltonSampler(uint64_t seed, int samplesPerPixel)
        : seed_(seed), lastIndex_(uint32_t(samplesPerPixel > 1 ? samplesPerPixel - 1 : 0)) {}
    void startPixelSample(int px, int py, int sampleIndex) override {
        pixelHash_ = pixelHash(px, py, seed_);
        index_ = uint32_t(sampleIndex);
        dimension_ = 0;
    }
    float get1D() override { return sample(dimension_++); }
    Vec2 get2D() override {
        float a = sample(dimension_);
        float b = sample(dimension_ + 1);
        dimension_ += 2;
        return {a, b};
    }
    std::unique_ptr<Sampler> clone() const override {
        return std::make_unique<HaltonSampler>(seed_, int(lastIndex_ + 1));
    }

private:
    float sample(uint32_t dimension) const {
        uint64_t h = mixWithKey(pixelHash_, dimension);
        // Beyond the prime table (paths of hundreds of bounces), plain independent values.
        if (dimension >= uint32_t(kPrimeCount)) return hashToUniform(mixWithKey(h, index_));
        return owenScrambledRadicalInverse(index_, lastIndex_, kPrimeDivisors[dimension], h);
    }

    uint64_t seed_;
    uint32_t lastIndex_;
    uint64_t pixelHash_ = 0;
    uint32_t index_ = 0, dimension_ = 0;
};

}  // namespace ps
