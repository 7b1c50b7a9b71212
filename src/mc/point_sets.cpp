#include "mc/point_sets.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "mc/sobol.h"
#include "mc/sobol_matrices.h"

namespace ps {

namespace {

// Largest k with k^s <= n.
int gridSide(int n, int dims) {
    int k = std::max(1, int(std::floor(std::pow(double(n), 1.0 / dims))));
    auto pw = [&](int b) {
        double p = 1;
        for (int d = 0; d < dims; ++d) p *= b;
        return p;
    };
    while (pw(k + 1) <= n) ++k;
    while (k > 1 && pw(k) > n) --k;
    return k;
}

// Keep jittered values strictly below 1 (double rounding of (j + u)/k can reach 1).
double below1(double x) { return x < 1.0 ? x : std::nextafter(1.0, 0.0); }

void independent(PointSet& p, Rng& rng) {
    for (double& x : p.data) x = rng.uniformDouble();
}

// One jittered point per cell of a k^s grid (thesis §2.7.1): cell c has digits c_d in base k.
void stratified(PointSet& p, Rng& rng) {
    int k = gridSide(p.n, p.dims);
    for (int i = 0; i < p.n; ++i) {
        int cell = i;
        for (int d = 0; d < p.dims; ++d) {
            p.data[size_t(i) * p.dims + d] = below1((cell % k + rng.uniformDouble()) / k);
            cell /= k;
        }
    }
}

// N-rooks: an independent random permutation of the n strata per dimension (McKay et al. 1979).
void latinHypercube(PointSet& p, Rng& rng) {
    std::vector<int> perm(p.n);
    for (int d = 0; d < p.dims; ++d) {
        std::iota(perm.begin(), perm.end(), 0);
        for (int i = p.n - 1; i > 0; --i) std::swap(perm[i], perm[rng.uniformInt(uint32_t(i + 1))]);
        for (int i = 0; i < p.n; ++i) p.data[size_t(i) * p.dims + d] = below1((perm[i] + rng.uniformDouble()) / p.n);
    }
}

// Owen scrambling with an independent seed per dimension keeps the net's stratification and
// makes each point uniform on the 2^-32 lattice (Owen 1995); a uniform fill below the last
// bit makes it uniform on [0,1), so no point sits exactly at 0 (where `singular` is infinite).
void sobol(PointSet& p, Rng& rng) {
    if (p.dims > kSobolMaxDims) throw std::invalid_argument("sobol points: at most 10 dimensions");
    for (int d = 0; d < p.dims; ++d) {
        uint32_t seed = rng.nextU32(), v = 0;
        for (int i = 0; i < p.n; ++i) {
            // Natural order, incrementally: i -> i+1 flips bits 0..t, t = ctz(i+1), so the
            // point changes by the xor of columns 0..t (sobolSample(i, d) == v).
            if (i > 0) v ^= sobolSample((2u << __builtin_ctz(uint32_t(i))) - 1, d);
            uint32_t x = owenScramble(v, seed);
            p.data[size_t(i) * p.dims + d] = (double(x) + rng.uniformDouble()) * 0x1p-32;
        }
    }
}

}  // namespace

std::optional<PointSetKind> pointSetKindFromName(const std::string& name) {
    if (name == "independent") return PointSetKind::Independent;
    if (name == "stratified") return PointSetKind::Stratified;
    if (name == "lhs") return PointSetKind::LatinHypercube;
    if (name == "sobol") return PointSetKind::Sobol;
    return std::nullopt;
}

const char* pointSetName(PointSetKind kind) {
    switch (kind) {
    case PointSetKind::Independent: return "independent";
    case PointSetKind::Stratified: return "stratified";
    case PointSetKind::LatinHypercube: return "lhs";
    case PointSetKind::Sobol: return "sobol";
    }
    return "?";
}

int pointSetSize(PointSetKind kind, int n, int dims) {
    if (kind != PointSetKind::Stratified) return n;
    int k = gridSide(n, dims), size = 1;
    for (int d = 0; d < dims; ++d) size *= k;
    return size;
}

PointSet generatePoints(PointSetKind kind, int n, int dims, Rng& rng) {
    if (n < 1 || dims < 1) throw std::invalid_argument("point set: need n >= 1 and dims >= 1");
    PointSet p;
    p.n = pointSetSize(kind, n, dims);
    p.dims = dims;
    p.data.resize(size_t(p.n) * dims);
    switch (kind) {
    case PointSetKind::Independent: independent(p, rng); break;
    case PointSetKind::Stratified: stratified(p, rng); break;
    case PointSetKind::LatinHypercube: latinHypercube(p, rng); break;
    case PointSetKind::Sobol: sobol(p, rng); break;
    }
    return p;
}

}  // namespace ps
