// Randomised orthogonal arrays (Owen 1992, "Orthogonal arrays for computer experiments,
// integration and visualization"), with Tang's (1993) Latin hypercube refinement: the
// samples of a pixel are stratified in every 2-D projection (a p x p jittered grid) and in
// every 1-D projection (p^2 strata), for any pair of dimensions in an array, not only for the
// pairs a 2-D request asks for.
#pragma once
#include "mc/sampler.h"

namespace ps {

// Bose's construction of OA(p^2, p + 1, p, 2), p prime: row (a, b) of Z_p^2 holds the
// symbol a + c b (mod p) in column c < p and b in column p. Any two columns map the rows
// one-to-one onto Z_p^2 (their coefficient matrix is invertible mod p), so each symbol pair
// occurs exactly once: strength 2.
inline uint32_t boseSymbol(uint32_t a, uint32_t b, uint32_t column, uint32_t p) {
    return column < p ? (a + column * b) % p : b;
}
// The p rows holding one symbol in a column differ in the coordinate the symbol leaves free.
inline uint32_t boseRank(uint32_t a, uint32_t b, uint32_t column, uint32_t p) { return column < p ? b : a; }

// The smallest prime p with p^2 >= n.
inline uint32_t orthogonalArrayBase(uint32_t n) {
    auto isPrime = [](uint32_t v) {
        for (uint32_t d = 2; d * d <= v; ++d)
            if (v % d == 0) return false;
        return true;
    };
    uint32_t p = 2;
    while (uint64_t(p) * p < n || !isPrime(p)) ++p;
    return p;
}

// Randomisation, per (pixel, seed, array): rows are shuffled, the symbols of each column
// permuted, the p rows sharing a symbol spread over its p sub-strata by another permutation
// (all random affine permutations of Z_p, see permutePrime), and each point jittered within
// its sub-stratum. Every point is then uniform on [0,1) (the estimate is unbiased) while the
// array's stratification survives.
//
// Dimensions are taken column by column; once an array's columns are used up the next
// dimensions read a fresh, independently randomised array (padding). Sample index i reads
// row i mod p^2; further rounds of p^2 samples re-randomise everything.
//
// When the sample count N is below p^2 only the first N rows are used. The row shuffle keeps
// rows in groups of p that share b, and within such a group columns c < p hold every symbol
// once, so a prefix of the rows stays balanced in those columns. Column p (= b) would not, so
// it is only used when N = p^2.
class OrthogonalArraySampler final : public Sampler {
public:
    OrthogonalArraySampler(uint64_t seed, int samplesPerPixel)
        : seed_(seed), n_(uint32_t(samplesPerPixel < 1 ? 1 : samplesPerPixel)), p_(orthogonalArrayBase(n_)),
          columns_(p_ * p_ == n_ ? p_ + 1 : p_), pDivisor_(p_) {}
    uint32_t base() const { return p_; }
    uint32_t columnsPerArray() const { return columns_; }

    void startPixelSample(int px, int py, int sampleIndex) override {
        pixelHash_ = pixelHash(px, py, seed_);
        row_ = uint32_t(sampleIndex) % (p_ * p_);
        round_ = uint32_t(sampleIndex) / (p_ * p_);
        array_ = 0;
        column_ = 0;
        rowReady_ = false;
    }
    float get1D() override { return value(takeColumns(1)); }
    Vec2 get2D() override {
        uint32_t c = takeColumns(2);  // a pair never straddles two arrays
        return {value(c), value(c + 1)};
    }
    std::unique_ptr<Sampler> clone() const override {
        return std::make_unique<OrthogonalArraySampler>(seed_, int(n_));
    }

private:
    // Reserves `count` consecutive columns of one array, moving to the next array when the
    // current one has fewer left, and returns the first. The array's key and this sample's
    // shuffled row in it are computed once per array.
    uint32_t takeColumns(uint32_t count) {
        if (column_ + count > columns_) {
            ++array_;
            column_ = 0;
            rowReady_ = false;
        }
        if (!rowReady_) {
            rowReady_ = true;
            arrayKey_ = hashCombine(pixelHash_, (uint64_t(round_) << 32) | array_);
            // Row index q p + t becomes (a, b) = (pi_q(t), tau(q)): a shuffle that keeps the groups of p.
            uint32_t q = row_ / p_, t = row_ % p_;
            a_ = permutePrime(t, pDivisor_, mixWithKey(arrayKey_, (1ULL << 40) + q));  // apart from column keys
            b_ = permutePrime(q, pDivisor_, arrayKey_);
        }
        uint32_t c = column_;
        column_ += count;
        return c;
    }
    // Per column: the symbol permutation, one sub-stratum permutation per symbol, and the
    // jitter per row, all from cheap hashes of the array's key.
    float value(uint32_t column) const {
        uint64_t h = mixWithKey(arrayKey_, column);
        uint32_t symbol = permutePrime(boseSymbol(a_, b_, column, p_), pDivisor_, h);
        uint32_t sub = permutePrime(boseRank(a_, b_, column, p_), pDivisor_, mixWithKey(h, symbol + 1));
        return jitteredStratum(symbol * p_ + sub, p_ * p_, hashToUniform(mixWithKey(h, 0x100000000ULL + row_)));
    }

    uint64_t seed_;
    uint32_t n_, p_, columns_;
    FastDivisor pDivisor_;
    uint64_t pixelHash_ = 0;
    uint32_t row_ = 0, round_ = 0;
    uint32_t array_ = 0, column_ = 0;  // the next column to read
    bool rowReady_ = false;
    uint32_t a_ = 0, b_ = 0;  // this sample's row in the current array
    uint64_t arrayKey_ = 0;
};

}  // namespace ps
