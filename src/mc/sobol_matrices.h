// Sobol generator matrices for the first ten dimensions, built from Joe and Kuo's direction
// numbers (new-joe-kuo-6.21201: degree s, polynomial coefficients a, initial m_1..m_s).
// sobol.h covers only dimensions 0 and 1 (enough for the renderer's 2-D padding); the
// Monte Carlo toolbox integrates in up to ten dimensions (thesis §2.7, quasi-Monte Carlo).
#pragma once
#include <array>
#include <cstdint>

namespace ps {

constexpr int kSobolMaxDims = 10;

namespace detail {

struct JoeKuoEntry {
    int s;            // degree of the primitive polynomial
    uint32_t a;       // its inner coefficients a_1..a_{s-1}, a_1 the most significant bit
    uint32_t m[5];    // initial direction integers m_1..m_s (m_k odd, m_k < 2^k)
};

// Dimension 0 is the van der Corput sequence (all m_k = 1); rows 1..9 are Joe-Kuo d = 2..10.
constexpr JoeKuoEntry kJoeKuo[kSobolMaxDims] = {
    {1, 0, {1}},  // unused recurrence: every m_k = 1
    {1, 0, {1}},          {2, 1, {1, 3}},       {3, 1, {1, 3, 1}},      {3, 2, {1, 1, 1}},
    {4, 1, {1, 1, 3, 3}}, {4, 4, {1, 3, 5, 13}}, {5, 2, {1, 1, 5, 5, 17}}, {5, 4, {1, 1, 5, 5, 5}},
    {5, 7, {1, 1, 7, 11, 19}},
};

// Bratley and Fox's recurrence: m_k = 2 a_1 m_{k-1} ^ 4 a_2 m_{k-2} ^ ... ^ 2^s m_{k-s} ^ m_{k-s};
// column k (0-based) of the matrix is v_{k+1} = m_{k+1} / 2^{k+1} as 32-bit fixed point.
constexpr std::array<uint32_t, 32> sobolColumns(int dim) {
    std::array<uint32_t, 32> v{};
    if (dim == 0) {
        for (int k = 0; k < 32; ++k) v[k] = 1u << (31 - k);
        return v;
    }
    const JoeKuoEntry& e = kJoeKuo[dim];
    uint64_t m[33]{};
    for (int k = 1; k <= 32; ++k) {
        if (k <= e.s) {
            m[k] = e.m[k - 1];
            continue;
        }
        uint64_t mk = m[k - e.s] ^ (m[k - e.s] << e.s);
        for (int j = 1; j < e.s; ++j)
            if ((e.a >> (e.s - 1 - j)) & 1u) mk ^= m[k - j] << j;
        m[k] = mk;
    }
    for (int k = 1; k <= 32; ++k) v[k - 1] = uint32_t(m[k] << (32 - k));
    return v;
}

constexpr std::array<std::array<uint32_t, 32>, kSobolMaxDims> makeSobolMatrices() {
    std::array<std::array<uint32_t, 32>, kSobolMaxDims> c{};
    for (int d = 0; d < kSobolMaxDims; ++d) c[d] = sobolColumns(d);
    return c;
}

inline constexpr auto kSobolMatrices = makeSobolMatrices();

}  // namespace detail

// Unscrambled Sobol point `index` in dimension `dim` (0 <= dim < kSobolMaxDims), 32-bit fixed
// point, in natural (not Gray-code) order, so the first 2^m points form a (t,m,s)-net.
constexpr uint32_t sobolSample(uint32_t index, int dim) {
    uint32_t r = 0;
    const auto& c = detail::kSobolMatrices[dim];
    for (int k = 0; index; index >>= 1, ++k)
        if (index & 1) r ^= c[k];
    return r;
}

}  // namespace ps
