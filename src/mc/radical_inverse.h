// Radical inverses in prime bases, the coordinates of the Halton sequence (thesis §2.7.2):
// index i = sum d_k b^k maps to sum d_k b^-(k+1), so the first b^k indices put one point
// in each interval [j b^-k, (j+1) b^-k).
#pragma once
#include <array>
#include <cstdint>
#include "mc/permutation.h"
#include "mc/rng.h"

namespace ps {

// The first 1024 primes, one base per Halton dimension (the last is 8161).
inline constexpr int kPrimeCount = 1024;
inline constexpr std::array<uint32_t, kPrimeCount> kPrimes = [] {
    std::array<uint32_t, kPrimeCount> primes{};
    int count = 0;
    for (uint32_t v = 2; count < kPrimeCount; ++v) {
        bool prime = true;
        for (int k = 0; k < count && primes[k] * primes[k] <= v; ++k)
            if (v % primes[k] == 0) {
                prime = false;
                break;
            }
        if (prime) primes[count++] = v;
    }
    return primes;
}();

inline constexpr std::array<FastDivisor, kPrimeCount> kPrimeDivisors = [] {
    std::array<FastDivisor, kPrimeCount> divisors{};
    for (int k = 0; k < kPrimeCount; ++k) divisors[k] = FastDivisor(kPrimes[k]);
    return divisors;
}();

inline double radicalInverse(uint64_t index, uint32_t base) {
    double inv = 1.0 / base, scale = inv, result = 0;
    for (; index; index /= base, scale *= inv) result += double(index % base) * scale;
    return result;
}

// Owen's nested scrambling in base b: digit k passes through a random permutation of
// {0..b-1} chosen by a hash of the seed and digits 0..k-1 (an affine one, see permutePrime). Points stay in distinct
// elementary intervals (the permutations are bijections within each parent interval) and
// each point becomes uniform on [0,1), so Halton estimates become unbiased.
//
// Digits are permuted as long as `index` or `limit` has any left; all indices up to limit
// (the largest index the caller will use together) are thus scrambled consistently. Below
// that, every digit of every such index is 0 and the nested permutations would produce i.i.d.
// uniform digits, so the remaining tail is drawn as one uniform value.
// `base` is a precomputed divisor (see kPrimeDivisors).
inline float owenScrambledRadicalInverse(uint32_t index, uint32_t limit, const FastDivisor& base, uint64_t seed) {
    const uint32_t b = base.d;
    double inv = 1.0 / b, scale = inv, result = 0;
    uint64_t h = seed;
    while (index | limit) {
        uint32_t next = base.quotient(index), digit = index - next * b;
        result += double(permutePrime(digit, base, h)) * scale;
        // The next digit's permutation depends on this digit (nesting), cheaply re-mixed.
        h = (h ^ (digit + 1)) * 0x9e3779b97f4a7c15ULL;
        h ^= h >> 32;
        h *= 0xbf58476d1ce4e5b9ULL;
        h ^= h >> 29;
        index = next;
        limit = base.quotient(limit);
        scale *= inv;
    }
    result += scale * b * hashToUniform(mix64(h));
    float u = float(result);
    return u < 1.0f ? u : 0x1.fffffep-1f;
}
inline float owenScrambledRadicalInverse(uint32_t index, uint32_t limit, uint32_t base, uint64_t seed) {
    return owenScrambledRadicalInverse(index, limit, FastDivisor(base), seed);
}

}  // namespace ps
