// The naive sequential stopping rule is biased; the two-stage scheme is not.
#include <gtest/gtest.h>

#include <cstdio>

#include "mc/adaptive_sampling.h"
#include "mc/test_integrands.h"
#include "mc_test_util.h"

using namespace ps;
using namespace ps::test;

TEST(AdaptiveSampling, SequentialStoppingRuleIsBiasedLow) {
    // f(u) = 1/(2 sqrt u), exact integral 1, heavy right tail: runs that have not yet seen a
    // large value have a small sample variance and stop early, so the mean is too low.
    TestIntegrand t = makeTestIntegrand("singular", 1);
    RunsSummary s = repeatRuns([&](Rng& rng) { return estimateSequential(t.f, 1, 0.05, 8, 100000, rng); }, 4000, 31);
    double bias = s.estimates.mean() - 1.0;
    std::printf("[ adaptive ] sequential: mean %.4f +- %.4f (bias %.1f sigma), %.0f samples per run\n",
                s.estimates.mean(), s.estimates.standardError(), bias / s.estimates.standardError(), s.meanEvaluations);
    EXPECT_LT(bias, -6 * s.estimates.standardError());
    // With a fixed sample count of about the same size the same estimator is unbiased.
    const int n = int(s.meanEvaluations);
    RunsSummary fixed = repeatRuns([&](Rng& rng) { return estimateSequential(t.f, 1, 0.0, n, n, rng); }, 4000, 32);
    std::printf("[ adaptive ] fixed n=%d: mean %.4f +- %.4f\n", n, fixed.estimates.mean(),
                fixed.estimates.standardError());
    EXPECT_LT(sigmasFrom(fixed.estimates, 1.0), 4.0);
}

TEST(AdaptiveSampling, TwoStageSamplingIsUnbiased) {
    for (const char* name : {"exp", "ball", "halfspace", "gaussian"}) {
        for (int dims : {1, 2, 4}) {
            TestIntegrand t = makeTestIntegrand(name, dims);
            TwoStageOptions o;
            o.cellsPerAxis = dims == 1 ? 8 : 4;
            o.pilotPerCell = 4;
            o.budget = 256;
            RunsSummary s = repeatRuns([&](Rng& rng) { return estimateTwoStage(t.f, dims, o, rng); }, 1000, 33);
            EXPECT_LT(sigmasFrom(s.estimates, t.exact), 4.0) << name << " s=" << dims;
            EXPECT_NEAR(s.meanEvaluations, 256.0, 1e-9);
        }
    }
}

TEST(AdaptiveSampling, TwoStageIsUnbiasedWhereTheSequentialRuleIsNot) {
    // The heavy-tailed case that biases the sequential rule: pilots that missed the tail
    // allocate few samples to the singular cell, but those samples are fresh, so only the
    // variance suffers, not the mean.
    TestIntegrand t = makeTestIntegrand("singular", 1);
    TwoStageOptions o;
    o.cellsPerAxis = 4;
    o.pilotPerCell = 4;
    o.budget = 128;
    RunsSummary s = repeatRuns([&](Rng& rng) { return estimateTwoStage(t.f, 1, o, rng); }, 4000, 34);
    std::printf("[ adaptive ] two-stage on singular: mean %.4f +- %.4f\n", s.estimates.mean(),
                s.estimates.standardError());
    EXPECT_LT(sigmasFrom(s.estimates, 1.0), 4.0);
    Rng rng(1);
    EXPECT_THROW(estimateTwoStage(t.f, 1, {8, 4, 10}, rng), std::invalid_argument);
}
