#include "mc/padded_strata.h"

#include <algorithm>

#include "mc/permutation.h"
#include "mc/rng.h"
#include "mc/sobol.h"

namespace ps {

PaddedStrata::PaddedStrata(uint64_t key, int64_t i, int64_t n) {
    const int64_t count = std::min<int64_t>(std::max<int64_t>(n, 1), int64_t(UINT32_MAX));
    key_ = mixWithKey(key, uint64_t(i / count));
    index_ = uint32_t(i % count);
    count_ = uint32_t(count);
}

double PaddedStrata::value(uint64_t pair, bool second) const {
    const uint64_t key = mixWithKey(key_, pair);
    const uint32_t p = permuteIndex(index_, count_, uint32_t(key));
    // Reversed Sobol points (sobol.h): dimension 0's is the index itself.
    const uint32_t v = !second ? owenScrambleReversed(p, uint32_t(key >> 32))
                               : owenScrambleReversed(sobolDim1Reversed(p), uint32_t(mix64(key) >> 32));
    return double(v) * 0x1p-32;
}

}  // namespace ps
