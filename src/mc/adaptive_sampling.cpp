#include "mc/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace ps {

McEstimate estimateSequential(const Integrand& f, int dims, double targetError, int minSamples, int maxSamples,
                              Rng& rng) {
    Stopwatch clock;
    RunningStats s;
    std::vector<double> u(static_cast<size_t>(dims));
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
    std::vector<double> u(static_cast<size_t>(dims));
    auto sampleCell = [&](int cell) {
        for (double& x : u) x = rng.uniformDouble();
        u[0] = (cell % k + u[0]) / k;
        if (gridDims == 2) u[1] = (cell / k + u[1]) / k;
        return f(u);
    };

    std::vector<double> sigma(static_cast<size_t>(cells));
    for (int c = 0; c < cells; ++c) {
        RunningStats pilot;
        for (int i = 0; i < o.pilotPerCell; ++i) pilot.add(sampleCell(c));
        sigma[c] = std::sqrt(pilot.variance());
    }

    // Neyman allocation of the second stage by largest remainders, 2 per cell guaranteed so
    // that every cell's variance can be estimated.
    int second = o.budget - cells * o.pilotPerCell, spare = second - 2 * cells;
    double total = 0;
    for (double s : sigma) total += s;
    std::vector<int> alloc(size_t(cells), 2);
    std::vector<double> remainder(static_cast<size_t>(cells));
    int given = 0;
    for (int c = 0; c < cells; ++c) {
        double share = total > 0 ? spare * sigma[c] / total : double(spare) / cells;
        alloc[c] += int(share);
        given += int(share);
        remainder[c] = share - int(share);
    }
    std::vector<int> order(static_cast<size_t>(cells));
    for (int c = 0; c < cells; ++c) order[c] = c;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return remainder[a] > remainder[b]; });
    for (int i = 0; given < spare; ++i, ++given) ++alloc[order[size_t(i) % order.size()]];

    double value = 0, variance = 0;
    for (int c = 0; c < cells; ++c) {
        RunningStats s;
        for (int i = 0; i < alloc[c]; ++i) s.add(sampleCell(c));
        value += volume * s.mean();
        variance += volume * volume * s.varianceOfMean();
    }
    return {value, std::sqrt(variance), int64_t(o.budget), clock.seconds()};
}

}  // namespace ps
