// PCG32 (O'Neill 2014): small state, good statistics, cheap to seed per pixel sample.
#pragma once
#include <cstdint>

namespace ps {

// SplitMix64 finaliser; used to derive independent stream seeds from (pixel, index, seed).
inline uint64_t mix64(uint64_t v) {
    v ^= v >> 31;
    v *= 0x7fb5d329728ea185ULL;
    v ^= v >> 27;
    v *= 0x81dadef4bc2dd44dULL;
    v ^= v >> 33;
    return v;
}
// A hash of (key, k) for an already well-mixed key: a cheap multiply-xorshift finaliser
// (SplitMix64's) suffices on hot paths such as one seed per sample dimension.
inline uint64_t mixWithKey(uint64_t key, uint64_t k) {
    uint64_t h = key ^ (k * 0x9e3779b97f4a7c15ULL);
    h *= 0xbf58476d1ce4e5b9ULL;
    h ^= h >> 31;
    h *= 0x94d049bb133111ebULL;
    return h ^ (h >> 29);
}

// The top 24 bits of a hash as a float in [0, 1).
inline float hashToUniform(uint64_t h) { return float(h >> 40) * 0x1p-24f; }
inline uint64_t hashCombine(uint64_t a, uint64_t b) { return mix64(a ^ (b + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2))); }

class Rng {
public:
    Rng() { seed(0, 0x853c49e6748fea9bULL); }
    explicit Rng(uint64_t seq, uint64_t init = 0x853c49e6748fea9bULL) { seed(seq, init); }
    void seed(uint64_t seq, uint64_t init) {
        state_ = 0;
        inc_ = (seq << 1) | 1;
        nextU32();
        state_ += init;
        nextU32();
    }
    uint32_t nextU32() {
        uint64_t old = state_;
        state_ = old * 0x5851f42d4c957f2dULL + inc_;
        uint32_t xorshifted = uint32_t(((old >> 18) ^ old) >> 27);
        uint32_t rot = uint32_t(old >> 59);
        return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
    }
    // Uniform in [0, 1), never 1.
    float uniform() { return float(nextU32() >> 8) * 0x1p-24f; }
    double uniformDouble() {
        uint64_t v = (uint64_t(nextU32()) << 21) ^ nextU32();
        return double(v & ((1ULL << 53) - 1)) * 0x1p-53;
    }
    // Uniform integer in [0, n).
    uint32_t uniformInt(uint32_t n) { return uint32_t((uint64_t(nextU32()) * n) >> 32); }
    void advance(int64_t delta);

private:
    uint64_t state_ = 0, inc_ = 1;
};

inline void Rng::advance(int64_t idelta) {
    uint64_t curMult = 0x5851f42d4c957f2dULL, curPlus = inc_, accMult = 1, accPlus = 0;
    uint64_t delta = uint64_t(idelta);
    while (delta > 0) {
        if (delta & 1) {
            accMult *= curMult;
            accPlus = accPlus * curMult + curPlus;
        }
        curPlus = (curMult + 1) * curPlus;
        curMult *= curMult;
        delta /= 2;
    }
    state_ = accMult * state_ + accPlus;
}

}  // namespace ps
