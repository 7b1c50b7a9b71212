// Sample i of a set of n whose values are stratified over the set, two at a time: pair k's
// two values are point i of the first n points of an Owen-scrambled (0,2)-sequence, each pair
// through its own random permutation of the points (padding, as PaddedSobolSampler pairs a
// pixel's dimensions; thesis §2.7 on stratification). Every value is still uniform on its
// own, which is all that an unbiased mean over the set uses; the set's mean has the lower
// variance of stratified samples. The Metropolis bootstraps use it (their mean weight b scales
// the whole image): PrimarySampleSampler::stratifyFirstIteration and Veach's mlt.
#pragma once
#include <cstdint>

namespace ps {

class PaddedStrata {
public:
    PaddedStrata() = default;  // no set: active() is false
    // Sets of more than 2^32 samples continue as further sets of their own (keyed apart).
    PaddedStrata(uint64_t key, int64_t i, int64_t n);
    bool active() const { return count_ > 0; }
    // Value `second` (0 or 1) of pair `pair` of this sample, in [0, 1).
    double value(uint64_t pair, bool second) const;

private:
    uint64_t key_ = 0;
    uint32_t index_ = 0, count_ = 0;  // count 0: none
};

}  // namespace ps
