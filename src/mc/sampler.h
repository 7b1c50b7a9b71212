// Sample placement behind one interface: for pixel (x, y) and sample index i, a
// deterministic stream of 1-D and 2-D values, independent of which thread asks.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>
#include "math/vec.h"
#include "mc/rng.h"
#include "mc/permutation.h"
#include "mc/sobol.h"

namespace ps {

class Sampler {
public:
    // Lets hot loops dispatch once to code specialised for a concrete sampler.
    enum class Kind { Independent, PaddedSobol, Other };
    virtual ~Sampler() = default;
    virtual Kind kind() const { return Kind::Other; }
    virtual void startPixelSample(int px, int py, int sampleIndex) = 0;
    virtual float get1D() = 0;
    virtual Vec2 get2D() = 0;
    // The film position within the pixel (its own dimension pair).
    virtual Vec2 getPixel2D() { return get2D(); }
    // Dimension streams (primary-sample-space Metropolis): an estimator that draws for
    // separate parts of a path selects each part's stream before drawing, so that what one
    // part consumes never shifts the values another reads. A no-op for samplers with one
    // stream, whose values then follow in the order drawn.
    virtual void startStream(int) {}
    // Within the current stream, the next value drawn is its index-th: a walk that reads a
    // fixed block of values per bounce keeps each bounce on its own values, whatever earlier
    // bounces drew conditionally (a lobe choice, Russian roulette). A no-op for samplers
    // with one stream.
    virtual void seekDimension(int) {}
    virtual std::unique_ptr<Sampler> clone() const = 0;
};

// The per-(pixel, seed) hash every sampler keys its randomisation on.
inline uint64_t pixelHash(int px, int py, uint64_t seed) {
    return hashCombine(mix64((uint64_t(uint32_t(px)) << 32) | uint32_t(py)), seed);
}

// Point s + j (j in [0,1) the jitter) of `count` equal strata of [0,1), kept below 1 after rounding.
inline float jitteredStratum(uint32_t s, uint32_t count, float j) {
    float u = (float(s) + j) / float(count);
    return u < 1.0f ? u : 0x1.fffffep-1f;
}

// Independent uniform samples (thesis §2.7.1's baseline): one PCG stream per pixel sample.
class IndependentSampler final : public Sampler {
public:
    explicit IndependentSampler(uint64_t seed) : seed_(seed) {}
    Kind kind() const override { return Kind::Independent; }
    void startPixelSample(int px, int py, int sampleIndex) override {
        rng_.seed(pixelHash(px, py, seed_), mix64(uint64_t(sampleIndex) ^ (seed_ << 20)));
    }
    float get1D() override { return rng_.uniform(); }
    Vec2 get2D() override {
        float a = rng_.uniform();
        return {a, rng_.uniform()};
    }
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<IndependentSampler>(seed_); }

private:
    uint64_t seed_;
    Rng rng_;
};

// The index permutations of PaddedSobolSampler for N = 2^m samples, tabulated: row r, entry
// i holds sample i's permuted index p and the reversed Sobol point of dimension 1 at p
// (dimension 0's reversed point is p itself). A pixel reads dimension d from row (d + o) mod
// rows, o drawn per pixel, so each pixel pairs its dimensions by its own draw of two random
// permutations: a single table shared by all pixels would give every pixel the same luck of
// pairing. Looking an entry up replaces three hashes per request.
struct SobolPermutationTable {
    static constexpr uint32_t kMaxSamples = 256, kRows = 128;  // 128 KiB at most
    std::vector<uint16_t> entries;  // (permuted index, reversed dimension-1 point) pairs
    SobolPermutationTable(int log2N, uint64_t seed);
    static bool covers(uint32_t n) { return (n & (n - 1)) == 0 && n <= kMaxSamples; }
};

// Owen-scrambled Sobol points per pixel, padded across dimensions (pbrt-v4's "paddedsobol"):
// every 1-D and 2-D request uses the first one or two Sobol dimensions, with its own scramble
// seed, keyed by (pixel, dimension, seed), and its own random permutation of the pixel's N
// sample indices. Each pixel's samples are stratified in every requested 1-D and 2-D
// projection (a (0,2)-net for power-of-two N). The index permutation is what decorrelates
// the requests: with one shared index, two requests' top bits would agree (or disagree) for
// all samples at once, whatever N, and an integrand coupling them would keep a fixed error.
class PaddedSobolSampler final : public Sampler {
public:
    PaddedSobolSampler(uint64_t seed, int samplesPerPixel);
    // The block of indices each permutation covers: N itself for a power of two up to
    // kLargestBlock; otherwise the power of four at or above N, and blocks of the table's 256
    // beyond it. A nested permutation of a power of four keeps every aligned block of 4^k
    // indices together, so the first 4^k samples of a block are a (0,2k,2)-net: a render that
    // stops early (`--time` with an unbounded --spp, an interrupt) keeps the stratification of
    // the samples it took. A permutation of all N indices would give such a prefix samples at
    // random indices: in each dimension, no better than independent ones (bench/README.md,
    // "Time-budgeted renders").
    static constexpr uint32_t kLargestBlock = 1u << 16;
    static uint32_t permutationBlock(int samplesPerPixel);
    Kind kind() const override { return Kind::PaddedSobol; }
    void startPixelSample(int px, int py, int sampleIndex) override {
        pixelHash_ = pixelHash(px, py, seed_);
        // Indices beyond the block continue in further blocks: aligned blocks of a Sobol
        // sequence make up its power-of-two prefixes, so each 2-D projection stays a net.
        // Each block pairs the dimensions anew (its own permutation keys and table rows).
        roundBase_ = uint32_t(sampleIndex) / n_ * n_;
        indexInRound_ = uint32_t(sampleIndex) - roundBase_;
        const uint64_t blockHash = roundBase_ ? mixWithKey(pixelHash_, roundBase_) : pixelHash_;
        permutationKey_ = blockHash ^ 0x5851f42d4c957f2dULL;
        if (table_) {
            column_ = table_->entries.data() + 2 * indexInRound_;
            rowOffset_ = uint32_t(blockHash >> 57);
            roundDim1_ = sobolDim1Reversed(roundBase_);
        }
        dimension_ = 0;
    }
    float get1D() override {
        uint64_t dim = dimension_++;
        uint64_t h = dimensionSeed(dim);
        const uint16_t* e = tableEntry(dim);
        uint32_t index = e ? roundBase_ + e[0] : permutedIndex(dim);
        return fixedToFloat(owenScrambleReversed(index, uint32_t(h)));
    }
    Vec2 get2D() override {
        uint64_t dim = dimension_;
        dimension_ += 2;
        uint64_t h = dimensionSeed(dim);
        uint32_t index, dim1;
        if (const uint16_t* e = tableEntry(dim)) {
            index = roundBase_ + e[0];
            dim1 = roundDim1_ ^ e[1];  // the transform is linear over GF(2), and the bits are disjoint
        } else {
            index = permutedIndex(dim);
            dim1 = sobolDim1Reversed(index);
        }
        return {fixedToFloat(owenScrambleReversed(index, uint32_t(h))),
                fixedToFloat(owenScrambleReversed(dim1, uint32_t(h >> 32)))};
    }
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<PaddedSobolSampler>(*this); }

private:
    // Scramble seeds per dimension from the (already well mixed) pixel hash.
    uint64_t dimensionSeed(uint64_t dim) const { return mixWithKey(pixelHash_, dim); }
    // This sample's entry for dimension dim, or null beyond the table (or without one).
    const uint16_t* tableEntry(uint64_t dim) const {
        if (!column_ || dim >= SobolPermutationTable::kRows) return nullptr;
        return column_ + (size_t((uint32_t(dim) + rowOffset_) & (SobolPermutationTable::kRows - 1)) << (log2N_ + 1));
    }
    // Beyond the table: a per-pixel nested permutation of the index's base-4 digits (as ZSobol's).
    uint32_t permutedIndex(uint64_t dim) const {
        return roundBase_ + permuteNested(indexInRound_, log2N_, permutationKey_ + dim * 0x9e3779b97f4a7c15ULL);
    }

    uint64_t seed_;
    uint32_t n_;  // the permutation block: permutationBlock(N)
    int log2N_;
    std::shared_ptr<const SobolPermutationTable> table_;  // shared by clones; null if N is not covered
    const uint16_t* column_ = nullptr;                     // this sample's entry in row 0
    uint32_t rowOffset_ = 0;                               // this pixel's o
    uint64_t pixelHash_ = 0, permutationKey_ = 0;
    uint32_t roundBase_ = 0, indexInRound_ = 0, roundDim1_ = 0;
    uint64_t dimension_ = 0;
};

// Calls f with the sampler as its concrete type where hot loops are compiled for it (padded
// Sobol, independent), else as Sampler: integrators dispatch once per camera sample instead
// of making a virtual call per sample value.
template <typename F>
decltype(auto) withConcreteSampler(Sampler& sampler, F&& f) {
    switch (sampler.kind()) {
        case Sampler::Kind::PaddedSobol: return f(static_cast<PaddedSobolSampler&>(sampler));
        case Sampler::Kind::Independent: return f(static_cast<IndependentSampler&>(sampler));
        default: return f(sampler);
    }
}

// Stratified sampling over a pixel's N samples (thesis §2.7.1), padded across dimensions:
// every 1-D request is jittered in N strata, sample i taking stratum pi_d(i) of a random
// permutation per (pixel, dimension). 2-D requests use an m x m jittered grid when N = m^2
// (stratified) or N-rooks (Latin hypercube) otherwise, and always in "lhs" mode.
class StratifiedSampler final : public Sampler {
public:
    StratifiedSampler(uint64_t seed, int samplesPerPixel, bool latinHypercube)
        : seed_(seed), n_(uint32_t(samplesPerPixel < 1 ? 1 : samplesPerPixel)), lhs_(latinHypercube) {
        uint32_t m = 1;
        while ((m + 1) * (m + 1) <= n_) ++m;
        gridSide_ = (!lhs_ && m * m == n_) ? m : 0;
    }
    void startPixelSample(int px, int py, int sampleIndex) override {
        pixelHash_ = pixelHash(px, py, seed_);
        index_ = uint32_t(sampleIndex);
        dimension_ = 0;
    }
    float get1D() override {
        uint64_t h = hashCombine(pixelHash_, dimension_++);
        return stratum(permuteIndex(index_ % n_, n_, uint32_t(h)), n_, jitter(h, 0));
    }
    Vec2 get2D() override {
        uint64_t h = hashCombine(pixelHash_, dimension_);
        dimension_ += 2;
        if (gridSide_) {
            uint32_t cell = permuteIndex(index_ % n_, n_, uint32_t(h));
            return {stratum(cell % gridSide_, gridSide_, jitter(h, 0)), stratum(cell / gridSide_, gridSide_, jitter(h, 1))};
        }
        return {stratum(permuteIndex(index_ % n_, n_, uint32_t(h)), n_, jitter(h, 0)),
                stratum(permuteIndex(index_ % n_, n_, uint32_t(h >> 32)), n_, jitter(h, 1))};
    }
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<StratifiedSampler>(seed_, int(n_), lhs_); }

private:
    // Beyond N samples the pattern repeats with fresh jitter (index_ / n_ enters the hash).
    float jitter(uint64_t h, uint64_t k) const {
        return hashToUniform(mix64(h ^ (uint64_t(index_) * 0x9e3779b97f4a7c15ULL) ^ (k << 62)));
    }
    static float stratum(uint32_t s, uint32_t count, float j) { return jitteredStratum(s, count, j); }
    uint64_t seed_;
    uint32_t n_, gridSide_ = 0;
    bool lhs_;
    uint64_t pixelHash_ = 0;
    uint32_t index_ = 0;
    uint64_t dimension_ = 0;
};

// Names: "independent", "sobol" (padded Owen-scrambled Sobol), "stratified", "lhs",
// "orthogonal" (randomised orthogonal arrays), "halton" (Owen-scrambled Halton), "zsobol"
// (Sobol indexed in Morton order across the image). nullptr for other names.
// samplesPerPixel sizes the strata of the stratified samplers; resolution (the film's larger
// side in pixels, 0 if unknown) tells ZSobol how many Morton digits to randomise.
std::unique_ptr<Sampler> createSampler(const std::string& name, uint64_t seed, int samplesPerPixel = 16,
                                       int resolution = 0);

// Every name createSampler accepts, the default first.
inline const std::vector<std::string>& samplerNames() {
    static const std::vector<std::string> names = {"sobol", "zsobol", "halton", "orthogonal", "stratified", "lhs", "independent"};
    return names;
}

}  // namespace ps
