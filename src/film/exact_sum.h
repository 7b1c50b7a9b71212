// Exact integer sums in 64 bits that widen to 128 bits only where they must: the film's
// per-pixel sums. A sum is the integer low + high 2^64, low a signed 64-bit word kept with
// the pixel, high in a block of high words that exists only once some sum of the block's
// pixels has left the 64-bit range (a light seen directly at thousands of samples). Integer
// addition is associative, so the sum is the same whatever the order of its terms, and so
// is where it ends up: whether a block was allocated changes how a sum is stored, never
// its value.
#pragma once
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>

namespace ps {

using Fixed = __int128;  // a sum as one integer (the film's accumulators, Film::Accumulators)

// Fixed(x) (truncation toward zero, |x| < 2^127) without the library call a compiler makes
// of a double-to-128-bit conversion (__fixdfti; the film alone took 8x as long as with
// double sums, bench/README.md). |x| = h 2^64 + l exactly: h 2^64 is exact and within a
// factor 2 of |x| when h > 0, so the subtraction is exact (Sterbenz), and l < 2^64.
inline Fixed truncateToFixed(double x) {
    const double a = std::fabs(x);
    const double h = std::floor(a * 0x1p-64);
    const Fixed f = Fixed(uint64_t(h)) << 64 | Fixed(uint64_t(a - h * 0x1p64));
    return x < 0 ? -f : f;
}

// Adds x (|x| < 2^126), rounded to the nearest integer, to the sum low + high 2^64 and
// returns what high must gain (zero unless the 64-bit word overflowed or x is that large).
inline int64_t addToSum(int64_t& low, double x) {
    if (std::fabs(x) < 0x1p62) {  // rounds to a 64-bit integer (from 2^53 on every double is one)
        const int64_t q = int64_t(std::nearbyint(x));
        // On overflow the wrapped word is the sum less (or plus) 2^64.
        if (!__builtin_add_overflow(low, q, &low)) return 0;
        return q > 0 ? 1 : -1;
    }
    const Fixed q = truncateToFixed(x);  // an integer already
    const int64_t ql = int64_t(uint64_t(q));
    int64_t carry = int64_t((q - ql) >> 64);
    if (__builtin_add_overflow(low, ql, &low)) carry += ql > 0 ? 1 : -1;
    return carry;
}

inline Fixed wideSum(int64_t low, int64_t high) { return Fixed(high) * (Fixed(1) << 64) + low; }

// Splits a sum into its words (the inverse of wideSum).
inline void splitSum(Fixed v, int64_t& low, int64_t& high) {
    low = int64_t(uint64_t(v));
    high = int64_t((v - low) >> 64);
}

// The high words of N sums per pixel, in blocks of kBlock pixels allocated on first need
// (all zero until then). A block may be asked for by two threads whose pixels share it:
// the first allocation wins, the other is freed. A pixel's words are written only by the
// thread that owns the pixel, as its low words are.
template <int N>
class HighWords {
public:
    static constexpr size_t kBlock = 64;
    explicit HighWords(size_t pixels = 0)
        : blockCount_((pixels + kBlock - 1) / kBlock),
          blocks_(blockCount_ ? std::make_unique<std::atomic<int64_t*>[]>(blockCount_) : nullptr) {}
    HighWords(HighWords&&) = delete;
    ~HighWords() {
        for (size_t b = 0; b < blockCount_; ++b) delete[] blocks_[b].load(std::memory_order_relaxed);
    }

    // Pixel i's N high words, or nullptr when its block was never needed (every word zero).
    const int64_t* find(size_t i) const {
        const int64_t* b = blocks_[i / kBlock].load(std::memory_order_acquire);
        return b ? b + (i % kBlock) * N : nullptr;
    }
    int64_t* at(size_t i) {
        std::atomic<int64_t*>& slot = blocks_[i / kBlock];
        int64_t* b = slot.load(std::memory_order_acquire);
        if (!b) {
            int64_t* fresh = new int64_t[kBlock * N]();
            if (slot.compare_exchange_strong(b, fresh, std::memory_order_acq_rel)) b = fresh;
            else delete[] fresh;  // another thread's block won; b is it
        }
        return b + (i % kBlock) * N;
    }
    // Adds a carry from addToSum to sum k of pixel i.
    void carry(size_t i, int k, int64_t c) {
        if (c != 0) at(i)[k] += c;
    }
    int64_t word(size_t i, int k) const {
        const int64_t* h = find(i);
        return h ? h[k] : 0;
    }

private:
    size_t blockCount_;
    std::unique_ptr<std::atomic<int64_t*>[]> blocks_;
};

}  // namespace ps
