// Russian roulette and splitting keep the mean and change variance and cost exactly as the
// closed forms say, on f(u1, u2) = u1 + u2: I = 1, E f^2 = 7/6, Var f = 1/6,
// Var E[f|u1] = 1/12, E Var[f|u1] = 1/12.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "mc/roulette_splitting.h"

using namespace ps;

namespace {

const Integrand kSum = [](std::span<const double> u) { return u[0] + u[1]; };
constexpr int kN = 400000;

// Per-sample variance from the estimate's standard error.
double perSampleVariance(const McEstimate& e, int samples) { return e.standardError * e.standardError * samples; }

}  // namespace

TEST(RussianRoulette, KeepsTheMeanAndMatchesTheClosedFormVarianceAndCost) {
    Rng rng(21);
    for (double q : {0.9, 0.5, 0.2}) {
        PointSet p = generatePoints(PointSetKind::Independent, kN, 3, rng);
        McEstimate e = estimateRoulette(kSum, 2, q, p);
        double predicted = 7.0 / (6.0 * q) - 1.0;
        double v = perSampleVariance(e, kN);
        std::printf("[ roulette ] q=%.1f variance %.4f (predicted %.4f), evaluations %lld (predicted %.0f)\n", q, v,
                    predicted, (long long)e.evaluations, q * kN);
        EXPECT_NEAR(e.value, 1.0, 4 * e.standardError);
        // The sample variance of 4e5 values is known to well under 1%.
        EXPECT_NEAR(v, predicted, 0.02 * predicted);
        EXPECT_NEAR(double(e.evaluations), q * kN, 4 * std::sqrt(kN * q * (1 - q)));
    }
}

TEST(Splitting, KeepsTheMeanAndMatchesTheClosedFormVarianceAndCost) {
    Rng rng(22);
    for (int k : {1, 2, 4, 8}) {
        const int samples = kN / k;
        PointSet p = generatePoints(PointSetKind::Independent, samples, splittingPointDims(2, 1, k), rng);
        McEstimate e = estimateSplitting(kSum, 2, 1, k, p);
        double predicted = 1.0 / 12 + 1.0 / (12.0 * k);
        double v = perSampleVariance(e, samples);
        std::printf("[ split    ] k=%d variance %.5f (predicted %.5f), evaluations %lld\n", k, v, predicted,
                    (long long)e.evaluations);
        EXPECT_NEAR(e.value, 1.0, 4 * e.standardError);
        EXPECT_NEAR(v, predicted, 0.03 * predicted);
        EXPECT_EQ(e.evaluations, int64_t(samples) * k);
    }
}

TEST(Splitting, CopiesUseTheirOwnSuffixCoordinates) {
    // splittingPointDims lays out prefix, then k suffix copies: check the layout directly.
    EXPECT_EQ(splittingPointDims(5, 2, 3), 2 + 3 * 3);
    PointSet p;
    p.n = 1;
    p.dims = splittingPointDims(3, 1, 2);  // u0 | (u1, u2) | (u1', u2')
    p.data = {0.1, 0.2, 0.3, 0.4, 0.5};
    std::vector<std::vector<double>> seen;
    Integrand record = [&](std::span<const double> u) {
        seen.emplace_back(u.begin(), u.end());
        return 0.0;
    };
    estimateSplitting(record, 3, 1, 2, p);
    ASSERT_EQ(seen.size(), 2u);
    EXPECT_EQ(seen[0], (std::vector<double>{0.1, 0.2, 0.3}));
    EXPECT_EQ(seen[1], (std::vector<double>{0.1, 0.4, 0.5}));
}
