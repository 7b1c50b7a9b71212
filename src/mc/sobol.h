// The first two dimensions of the Sobol sequence, a (0,2)-sequence in base 2, with
// hash-based Owen scrambling (Burley 2020, "Practical Hash-based Owen Scrambling"). Owen's
// nested uniform scrambling keeps every elementary-interval property of the net while making
// each point uniformly distributed, so estimates stay unbiased (thesis §2.7: stratification
// and quasi-Monte Carlo).
#pragma once
#include <cstdint>

namespace ps {

inline uint32_t reverseBits32(uint32_t v) {
    v = __builtin_bswap32(v);
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    return ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
}

// Dimension 0: the van der Corput radical inverse in base 2, as 32-bit fixed point.
inline uint32_t sobolDim0(uint32_t index) { return reverseBits32(index); }

// Dimension 1: generator matrix from the primitive polynomial x + 1, whose columns are
// the rows of Pascal's triangle mod 2: v_1 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1).
inline uint32_t sobolDim1(uint32_t index) {
    uint32_t result = 0, v = 1u << 31;
    for (; index; index >>= 1, v ^= v >> 1)
        if (index & 1) result ^= v;
    return result;
}

// Owen scrambling works on the bit-reversed value (the hash of each prefix must reach the
// bits below it, which multiplication only carries upwards). Points computed directly in
// reversed form save two reversals: owenScrambleReversed(sobolDim1Reversed(i), seed) ==
// owenScramble(sobolDim1(i), seed), and for dimension 0 the reversed point is i itself.
//
// In reversed form output bit r is the XOR of the index bits j with C(j, r) odd, which by
// Lucas' theorem are the j whose set bits include r's: a superset-XOR transform, done in
// five word-wide steps instead of a loop over the index bits.
inline uint32_t sobolDim1Reversed(uint32_t index) {
    uint32_t x = index;
    x ^= (x >> 1) & 0x55555555u;
    x ^= (x >> 2) & 0x33333333u;
    x ^= (x >> 4) & 0x0F0F0F0Fu;
    x ^= (x >> 8) & 0x00FF00FFu;
    return x ^ ((x >> 16) & 0x0000FFFFu);
}
inline uint32_t owenScrambleReversed(uint32_t v, uint32_t seed) {
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return reverseBits32(v);
}

// 64-bit indices, for one sequence indexed across a whole image (ZSobol). To 32 output bits,
// dimension 0 ignores index bits >= 32, and dimension 1's generator column j equals column
// j mod 32 (Lucas: C(j, k) mod 2 for k < 32 depends on j mod 32 only), so the high word of
// the index folds onto the low one. Both return the reversed form.
inline uint32_t sobolDim0Reversed64(uint64_t index) { return uint32_t(index); }
inline uint32_t sobolDim1Reversed64(uint64_t index) { return sobolDim1Reversed(uint32_t(index) ^ uint32_t(index >> 32)); }

// Owen scrambling of a 32-bit fixed-point value: a hash of each prefix of bits decides
// whether the next bit flips (the Laine-Karras construction with Burley's constants).
inline uint32_t owenScramble(uint32_t v, uint32_t seed) { return owenScrambleReversed(reverseBits32(v), seed); }

// 32-bit fixed point to a float in [0, 1).
inline float fixedToFloat(uint32_t v) { return float(v >> 8) * 0x1p-24f; }

}  // namespace ps
