// Random permutations of {0..n-1} evaluated one element at a time, without storing them:
// Kensler's hash-based permutation ("Correlated Multi-Jittered Sampling", 2013) with cycle
// walking to stay below n. Needed to stratify samples per pixel without per-pixel tables.
#pragma once
#include <array>
#include <cstdint>

namespace ps {

inline uint32_t permuteIndex(uint32_t i, uint32_t n, uint32_t seed) {
    if (n <= 1) return 0;
    uint32_t w = n - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    do {
        i ^= seed;
        i *= 0xe170893du;
        i ^= seed >> 16;
        i ^= (i & w) >> 4;
        i ^= seed >> 8;
        i *= 0x0929eb3fu;
        i ^= seed >> 23;
        i ^= (i & w) >> 1;
        i *= 1 | seed >> 27;
        i *= 0x6935fa69u;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303u;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3u;
        i ^= (i & w) >> 2;
        i *= 0xc860a3dfu;
        i &= w;
        i ^= i >> 5;
    } while (i >= n);
    return n == w + 1 ? (i + seed) & w : (i + seed) % n;  // no division for powers of two
}

// Exact division of 32-bit numbers by a fixed divisor with one wide multiply (Lemire,
// Kaser & Kurz 2019, "Faster remainder by direct computation"): hardware divides would
// dominate the digit loops that use it.
struct FastDivisor {
    uint32_t d = 1;
    uint64_t m = 0;
    constexpr FastDivisor() = default;
    constexpr explicit FastDivisor(uint32_t divisor) : d(divisor), m(~0ULL / divisor + 1) {}
    uint32_t quotient(uint32_t n) const {
        return d == 1 ? n : uint32_t((static_cast<unsigned __int128>(m) * n) >> 64);
    }
    uint32_t remainder(uint32_t n) const { return n - quotient(n) * d; }
};

// A random affine permutation x -> (a x + c) mod p of Z_p, p prime (below 2^16), with a != 0
// and c drawn from the hash h. Any two distinct elements land on a uniformly random pair of
// distinct positions (the family is pairwise uniform), and the variance of scrambled-net and
// randomised-orthogonal-array estimates depends only on such pairs (Owen 2003, "Variance with
// alternative scramblings of digital nets"; Matousek 1998), so it randomises as well as a
// uniform permutation, for one multiply and one reduction.
inline uint32_t permutePrime(uint32_t x, const FastDivisor& p, uint64_t h) {
    uint32_t a = 1 + uint32_t((uint64_t(uint32_t(h)) * (p.d - 1)) >> 32);
    uint32_t c = uint32_t(((h >> 32) * p.d) >> 32);
    return p.remainder(a * x + c);
}

// Nested random permutations of an index, base-4 digit by digit: each digit goes through one
// of the 24 permutations of {0,1,2,3}, chosen by a hash of all bits above it and a key. Being
// nested from the top, the map is one-to-one and keeps every aligned block of 4^k indices
// together (ZSobol relies on both); keyed per dimension, it pairs the samples of different
// dimensions at random.
inline constexpr std::array<std::array<uint8_t, 4>, 24> kPermutations4 = [] {
    std::array<std::array<uint8_t, 4>, 24> table{};
    int n = 0;
    for (uint8_t a = 0; a < 4; ++a)
        for (uint8_t b = 0; b < 4; ++b)
            for (uint8_t c = 0; c < 4; ++c)
                if (a != b && a != c && b != c) table[n++] = {a, b, c, uint8_t(6 - a - b - c)};
    return table;
}();
// A cheap multiply-xorshift hash of the bits above a digit: called once per digit.
inline uint64_t digitHash(uint64_t higherBits, uint64_t key) {
    uint64_t v = (higherBits ^ key) * 0xbf58476d1ce4e5b9ULL;
    v ^= v >> 31;
    return v * 0x94d049bb133111ebULL;
}
// Digits [from, to) of index, digit d being bits 2d - odd and 2d - odd + 1 (odd = 1 leaves
// bit 0 to permuteLowestBit); returns only those digits' bits, permuted.
inline uint64_t permuteBase4Digits(uint64_t index, int from, int to, int odd, uint64_t key) {
    uint64_t result = 0;
    for (int d = from; d < to; ++d) {
        int shift = 2 * d - odd;
        uint32_t digit = uint32_t(index >> shift) & 3;
        uint32_t perm = uint32_t((uint64_t(digitHash(index >> (shift + 2), key) >> 32) * 24) >> 32);
        result |= uint64_t(kPermutations4[perm][digit]) << shift;
    }
    return result;
}
// Bit 0 as a base-2 digit, flipped by a hash of the bits above it.
inline uint64_t permuteLowestBit(uint64_t index, uint64_t key) {
    return (index & 1) ^ (digitHash(index >> 1, key) >> 63);
}
// A nested random permutation of [0, 2^m).
inline uint32_t permuteNested(uint32_t i, int m, uint64_t key) {
    const int odd = m & 1;
    uint64_t result = permuteBase4Digits(i, odd, (m + 1) / 2, odd, key);
    if (odd) result |= permuteLowestBit(i, key);
    return uint32_t(result);
}

}  // namespace ps
