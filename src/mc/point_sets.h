// Point sets of N points in [0,1)^s for the Monte Carlo toolbox (thesis §2.7): independent,
// jittered stratified (a k^s grid), Latin hypercube and Owen-scrambled Sobol. Every set is
// randomised so that each point is uniformly distributed and estimates stay unbiased.
// Unlike the renderer's per-pixel samplers (sampler.h), these produce whole sets at once.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mc/rng.h"

namespace ps {

enum class PointSetKind { Independent, Stratified, LatinHypercube, Sobol };

// "independent", "stratified", "lhs", "sobol".
std::optional<PointSetKind> pointSetKindFromName(const std::string& name);
const char* pointSetName(PointSetKind kind);

// n points in s dimensions, row-major: point i is data[i*dims .. i*dims+dims).
struct PointSet {
    int n = 0, dims = 0;
    std::vector<double> data;
    std::span<const double> point(int i) const { return {data.data() + size_t(i) * dims, size_t(dims)}; }
};

// Number of points the kind actually produces when asked for n: the stratified grid has
// k^s points with k = floor(n^(1/s)) (at least 1 per axis); the others produce n.
int pointSetSize(PointSetKind kind, int n, int dims);

// Sobol is limited to kSobolMaxDims dimensions (sobol_matrices.h); throws std::invalid_argument beyond.
PointSet generatePoints(PointSetKind kind, int n, int dims, Rng& rng);

}  // namespace ps
