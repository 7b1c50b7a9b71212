// Integer sample allocation over pixels, shared by the adaptive renderers (thesis ch. 2,
// "Adaptive sampling"): deterministic, so a seed still fixes the image.
#pragma once
#include <cstddef>
#include <vector>

namespace ps {

// Splits `total` samples over weights.size() pixels in proportion to the weights, with at
// least `minimum` each (so the sum exceeds `total` when minimum * size does). Rounding by
// largest remainder, ties to the lower index. Zero or non-finite weights throughout give a
// uniform split.
std::vector<int> proportionalAllocation(const std::vector<double>& weights, long long total, int minimum = 1);

// Indices of the k largest values (ties to the lower index), in increasing index order.
std::vector<size_t> largestK(const std::vector<double>& values, size_t k);

}  // namespace ps
