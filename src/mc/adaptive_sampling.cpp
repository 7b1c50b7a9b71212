#include "mc/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace ps {

namespace {

// Neyman allocation of `total` samples in proportion to sigma_j (equal cell volumes), by
// largest remainders, with 2 per cell guaranteed so every cell's variance can be estimated.
std::vector<int> neymanAllocation(const std::vector<double>& sigma, int total) {
    const int cells = int(sigma.size());
    int spare = total - 2 * cells, given = 0;
    double sum = 0;
    for (double s : sigma) sum += s;
    std::vector<int> alloc(sigma.size(), 2);
    std::vector<double> remainder(sigma.size());
    for (int c = 0; c < cells; ++c) {
        double share = sum > 0 ? spare * sigma[c] / sum : double(spare) / cells;
        alloc[c] += int(share);
        given += int(share);
        remainder[c] = share - int(share);
    }
    std::vector<int> order(sigma.size());
    for (int c = 0; c < cells; ++c) order[c] = c;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return remainder[a] > remainder[b]; });
    for (int i = 0; given < spare; ++i, ++given) ++alloc[order[size_t(i) % order.size()]];
    return alloc;
}

// Cells of a k x k grid over the first two coordinates (k cells along the first when dims = 1).
struct CellGrid {
    int dims, gridDims, k;
};

// `count` uniform samples of f within one cell; u is scratch space of size dims.
RunningStats sampleCell(const Integrand& f, const CellGrid& g, int cell, int count, std::span<double> u, Rng& rng) {
    RunningStats s;
    for (int i = 0; i < count; ++i) {
        for (double& x : u) x = rng.uniformDouble();
        u[0] = (cell % g.k + u[0]) / g.k;
        if (g.gridDims == 2) u[1] = (cell / g.k + u[1]) / g.k;
        s.add(f(u));
    }
    return s;
}

}  // namespace

McEstimate estimateSequential(const Integrand& f, int dims, double targetError, int minSamples, int maxSamples,
                              Rng& rng) {
    Stopwatch clock;
    RunningStats s;
    std::vector<double> u(static_cast<size_t>(dims));
    clearUpperVectorState();
    while (s.count() < maxSamples) {
        for (double& x : u) x = rng.uniformDouble();
        s.add(f(u));
        if (s.count() >= minSamples && s.standardError() <= targetError) break;
    }
    return estimateFromStats(s, s.count(), clock.seconds());
}

McEstimate estimateTwoStage(const Integrand& f, int dims, const TwoStageOptions& o, Rng& rng) {
    Stopwatch clock;
    const int gridDims = std::min(dims, 2), k = std::max(1, o.cellsPerAxis);
    const int cells = gridDims == 2 ? k * k : k;
    const double volume = 1.0 / cells;
    if (o.pilotPerCell < 2 || o.budget < cells * (o.pilotPerCell + 2))
        throw std::invalid_argument("two-stage sampling: budget too small for the cells");
    const CellGrid grid{dims, gridDims, k};
    std::vector<double> sigma(static_cast<size_t>(cells)), u(static_cast<size_t>(dims));
    clearUpperVectorState();
    for (int c = 0; c < cells; ++c) sigma[c] = std::sqrt(sampleCell(f, grid, c, o.pilotPerCell, u, rng).variance());

    std::vector<int> alloc = neymanAllocation(sigma, o.budget - cells * o.pilotPerCell);
    clearUpperVectorState();

    double value = 0, variance = 0;
    for (int c = 0; c < cells; ++c) {
        RunningStats s = sampleCell(f, grid, c, alloc[c], u, rng);
        value += volume * s.mean();
        variance += volume * volume * s.varianceOfMean();
    }
    return {value, std::sqrt(variance), int64_t(o.budget), clock.seconds()};
}

}  // namespace ps
