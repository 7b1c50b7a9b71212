// Random permutations of {0..n-1} evaluated one element at a time, without storing them:
// Kensler's hash-based permutation ("Correlated Multi-Jittered Sampling", 2013) with cycle
// walking to stay below n. Needed to stratify samples per pixel without per-pixel tables.
#pragma once
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
    return (i + seed) % n;
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

}  // namespace ps
