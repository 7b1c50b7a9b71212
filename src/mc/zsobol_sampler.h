// One Owen-scrambled Sobol sequence for the whole image, indexed in Morton (Z) order of the
// pixels (Ahmed & Wonka 2020, "Screen-space blue-noise diffusion of Monte Carlo sampling
// error via hierarchical ordering of pixels"; pbrt-v4's ZSobolSampler). Pixel (x, y) with
// N = 2^m samples owns the index block [morton(x, y) N, (morton(x, y) + 1) N), an aligned
// block of a (0,2)-sequence and hence a (0,m,2)-net. The base-4 digits of the index are
// permuted, each by a permutation chosen by a hash of the digits above it and of the
// dimension: the map stays one-to-one and keeps each pixel's block aligned (so its net),
// while neighbouring pixels get complementary parts of the sequence, which spreads the
// error over the image as blue noise instead of white noise.
#pragma once
#include <array>
#include "mc/permutation.h"
#include "mc/sampler.h"

namespace ps {

// Interleaves the bits of x (even bits) and y (odd bits).
inline uint64_t encodeMorton2(uint32_t x, uint32_t y) {
    auto spread = [](uint64_t v) {
        v = (v | (v << 16)) & 0x0000ffff0000ffffULL;
        v = (v | (v << 8)) & 0x00ff00ff00ff00ffULL;
        v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0fULL;
        v = (v | (v << 2)) & 0x3333333333333333ULL;
        return (v | (v << 1)) & 0x5555555555555555ULL;
    };
    return spread(x) | (spread(y) << 1);
}

class ZSobolSampler final : public Sampler {
public:
    // resolution: the film's larger side; 0 if unknown (then 2^16 is assumed).
    ZSobolSampler(uint64_t seed, int samplesPerPixel, int resolution)
        : seed_(seed), seedKey_(mix64(seed)), resolution_(resolution) {
        while ((1 << log2Spp_) < samplesPerPixel && log2Spp_ < 30) ++log2Spp_;
        int log2Res = 0;
        while ((1 << log2Res) < (resolution > 0 ? resolution : 1 << 16) && log2Res < 16) ++log2Res;
        base4Digits_ = log2Res + (log2Spp_ + 1) / 2;
    }
    uint32_t samplesPerPixel() const { return 1u << log2Spp_; }

    void startPixelSample(int px, int py, int sampleIndex) override {
        uint32_t i = uint32_t(sampleIndex);
        uint64_t pixel = encodeMorton2(uint32_t(px), uint32_t(py));
        mortonIndex_ = (pixel << log2Spp_) | (i & ((1u << log2Spp_) - 1));
        // Beyond N samples the pixel keeps its block and takes fresh scrambles.
        scrambleKey_ = hashCombine(seed_, i >> log2Spp_);
        dimension_ = 0;
        if (pixel != cachedPixel_) {
            cachedPixel_ = pixel;
            if (++generation_ == 0) {  // wrapped: forget every stamp
                cacheStamp_.fill(0);
                generation_ = 1;
            }
        }
    }
    float get1D() override {
        uint64_t index = permutedIndex(dimension_);
        uint64_t h = mixWithKey(scrambleKey_, dimension_++);
        return fixedToFloat(owenScrambleReversed(sobolDim0Reversed64(index), uint32_t(h)));
    }
    Vec2 get2D() override {
        uint64_t index = permutedIndex(dimension_);
        uint64_t h = mixWithKey(scrambleKey_, dimension_);
        dimension_ += 2;
        return {fixedToFloat(owenScrambleReversed(sobolDim0Reversed64(index), uint32_t(h))),
                fixedToFloat(owenScrambleReversed(sobolDim1Reversed64(index), uint32_t(h >> 32)))};
    }
    std::unique_ptr<Sampler> clone() const override {
        return std::make_unique<ZSobolSampler>(seed_, int(samplesPerPixel()), resolution_);
    }

    // The Sobol index of the current pixel sample in a dimension (exposed for tests).
    uint64_t permutedIndex(uint64_t dimension) {
        // With m odd the lowest index bit is a base-2 digit of its own, so base-4 digits
        // still line up with the pixel's Morton digits, which start at digit (m + 1) / 2.
        const int odd = log2Spp_ & 1, firstPixelDigit = (log2Spp_ + 1) / 2;
        // The digit hash finishes the mixing, as SplitMix64 does for seed + k * golden ratio.
        const uint64_t key = seedKey_ + dimension * 0x9e3779b97f4a7c15ULL;
        // The pixel's digits depend on the pixel and dimension only: samples of one pixel
        // reuse them (memoisation; the values do not depend on the order of requests).
        uint64_t result;
        if (dimension < kCachedDimensions && cacheStamp_[dimension] == generation_) {
            result = cachedPixelDigits_[dimension];
        } else {
            result = permuteBase4Digits(mortonIndex_, firstPixelDigit, base4Digits_, odd, key);
            // Bits above the randomised digits (pixels beyond the stated resolution) pass
            // through unchanged, which keeps the map one-to-one for any pixel.
            const int top = 2 * base4Digits_ - odd;
            if (top < 64) result |= (mortonIndex_ >> top) << top;
            if (dimension < kCachedDimensions) {
                cachedPixelDigits_[dimension] = result;
                cacheStamp_[dimension] = generation_;
            }
        }
        result |= permuteBase4Digits(mortonIndex_, odd, firstPixelDigit, odd, key);
        if (odd) result |= permuteLowestBit(mortonIndex_, key);
        return result;
    }

private:
    static constexpr uint64_t kCachedDimensions = 256;

    uint64_t seed_, seedKey_;
    int resolution_;
    int log2Spp_ = 0, base4Digits_ = 0;
    uint64_t mortonIndex_ = 0, scrambleKey_ = 0;
    uint64_t dimension_ = 0;
    uint64_t cachedPixel_ = ~0ULL;
    uint32_t generation_ = 0;
    std::array<uint32_t, kCachedDimensions> cacheStamp_{};
    std::array<uint64_t, kCachedDimensions> cachedPixelDigits_{};
};

}  // namespace ps
