#include "mc/techniques.h"

#include <algorithm>
#include <cmath>

#include "mc/adaptive_sampling.h"
#include "mc/antithetic.h"
#include "mc/control_variates.h"
#include "mc/expected_values.h"
#include "mc/importance_sampling.h"
#include "mc/plain_estimator.h"
#include "mc/point_sets.h"
#include "mc/regression.h"
#include "mc/roulette_splitting.h"
#include "mc/sobol_matrices.h"

namespace ps {

namespace {

constexpr double kRouletteSurvival = 0.5;
constexpr int kSplitting = 4;

bool always(const TestIntegrand&) { return true; }

// Times the whole run, point generation included.
template <class F>
McEstimate timed(F&& body) {
    Stopwatch clock;
    McEstimate e = body();
    e.seconds = clock.seconds();
    return e;
}

McEstimate onPoints(PointSetKind kind, const TestIntegrand& t, int n, Rng& rng) {
    return timed([&] { return estimatePlain(t.f, generatePoints(kind, n, t.dims, rng)); });
}

// Controls u_j - 1/2 (integral 0 each): cheap and correlated with any f that trends along
// the axes; their sum is the single control of the control-variate technique.
std::vector<ControlFunction> coordinateControls(int dims) {
    std::vector<ControlFunction> c;
    for (int j = 0; j < dims; ++j) c.push_back({[j](std::span<const double> u) { return u[size_t(j)]; }, 0.5});
    return c;
}
ControlFunction sumControl(int dims) {
    return {[](std::span<const double> u) {
                double s = 0;
                for (double v : u) s += v;
                return s;
            },
            0.5 * dims};
}

// Grid cells for the two-stage scheme: about n/16 cells, 4 pilot samples each (a quarter of
// the budget), the rest allocated by the pilots.
TwoStageOptions twoStageOptions(int dims, int n) {
    TwoStageOptions o;
    int cells = std::max(1, n / 16), gridDims = std::min(dims, 2);
    o.cellsPerAxis = std::max(1, int(std::floor(std::pow(double(cells), 1.0 / gridDims))));
    o.pilotPerCell = 4;
    o.budget = n;
    return o;
}

const std::vector<Technique> kTechniques = {
    {"independent", "plain Monte Carlo, independent uniform points", always,
     [](const TestIntegrand& t, int n, Rng& rng) { return onPoints(PointSetKind::Independent, t, n, rng); }},
    {"stratified", "one jittered point per cell of a k^s grid (k^s <= n points)", always,
     [](const TestIntegrand& t, int n, Rng& rng) { return onPoints(PointSetKind::Stratified, t, n, rng); }},
    {"lhs", "Latin hypercube (n strata in every coordinate)", always,
     [](const TestIntegrand& t, int n, Rng& rng) { return onPoints(PointSetKind::LatinHypercube, t, n, rng); }},
    {"sobol", "Owen-scrambled Sobol points (randomised quasi-Monte Carlo)",
     [](const TestIntegrand& t) { return t.dims <= kSobolMaxDims; },
     [](const TestIntegrand& t, int n, Rng& rng) { return onPoints(PointSetKind::Sobol, t, n, rng); }},
    {"antithetic", "n/2 pairs f(u), f(1-u)", always,
     [](const TestIntegrand& t, int n, Rng& rng) {
         return timed([&] {
             return estimateAntithetic(t.f, generatePoints(PointSetKind::Independent, std::max(1, n / 2), t.dims, rng));
         });
     }},
    {"control", "control variate sum(u_i), beta estimated", always,
     [](const TestIntegrand& t, int n, Rng& rng) {
         return timed([&] {
             return estimateControlVariateOptimal(t.f, sumControl(t.dims),
                                                  generatePoints(PointSetKind::Independent, n, t.dims, rng))
                 .estimate;
         });
     }},
    {"regression", "least squares on the controls u_1..u_s", always,
     [](const TestIntegrand& t, int n, Rng& rng) {
         return timed([&] {
             return estimateRegression(t.f, coordinateControls(t.dims),
                                       generatePoints(PointSetKind::Independent, n, t.dims, rng))
                 .estimate;
         });
     }},
    {"expected", "last coordinate integrated analytically", [](const TestIntegrand& t) { return bool(t.partial); },
     [](const TestIntegrand& t, int n, Rng& rng) {
         return timed([&] {
             return estimateExpectedValues(t.partial, t.dims,
                                           generatePoints(PointSetKind::Independent, n, std::max(1, t.dims - 1), rng));
         });
     }},
    {"importance", "importance sampling from a density resembling f",
     [](const TestIntegrand& t) { return t.importance.has_value(); },
     [](const TestIntegrand& t, int n, Rng& rng) {
         return timed([&] {
             return estimateImportance(t.f, *t.importance, generatePoints(PointSetKind::Independent, n, t.dims, rng));
         });
     }},
    {"roulette", "Russian roulette, survival 1/2 (about n/2 evaluations)", always,
     [](const TestIntegrand& t, int n, Rng& rng) {
         return timed([&] {
             return estimateRoulette(t.f, t.dims, kRouletteSurvival,
                                     generatePoints(PointSetKind::Independent, n, t.dims + 1, rng));
         });
     }},
    {"splitting", "last coordinate split 4 ways (n/4 samples)", always,
     [](const TestIntegrand& t, int n, Rng& rng) {
         int prefix = t.dims - 1;
         return timed([&] {
             return estimateSplitting(t.f, t.dims, prefix, kSplitting,
                                      generatePoints(PointSetKind::Independent, std::max(1, n / kSplitting),
                                                     splittingPointDims(t.dims, prefix, kSplitting), rng));
         });
     }},
    {"two-stage", "adaptive: pilots allocate the rest over grid cells (unbiased)", always,
     [](const TestIntegrand& t, int n, Rng& rng) {
         return timed([&] { return estimateTwoStage(t.f, t.dims, twoStageOptions(t.dims, n), rng); });
     }},
};

}  // namespace

const std::vector<Technique>& techniques() { return kTechniques; }

const Technique* findTechnique(const std::string& name) {
    for (const Technique& t : kTechniques)
        if (t.name == name) return &t;
    return nullptr;
}

}  // namespace ps
