#include <gtest/gtest.h>

#include "mc/estimator.h"
#include "mc/rng.h"

using namespace ps;

TEST(RunningStats, MatchesTwoPassFormulasAndIsStable) {
    // Values with a huge offset: the naive sum-of-squares formula loses every digit here.
    Rng rng(5);
    std::vector<double> xs;
    RunningStats s;
    for (int i = 0; i < 10000; ++i) {
        double x = 1e9 + rng.uniformDouble();
        xs.push_back(x);
        s.add(x);
    }
    double mean = 0;
    for (double x : xs) mean += x;
    mean /= xs.size();
    double var = 0;
    for (double x : xs) var += (x - mean) * (x - mean);
    var /= xs.size() - 1;
    EXPECT_NEAR(s.mean(), mean, 1e-5);  // 1e-14 relative
    EXPECT_NEAR(s.variance(), var, 1e-6 * var);
    EXPECT_NEAR(s.variance(), 1.0 / 12, 0.01);  // uniform [0,1)
}

TEST(RunningStats, MergeEqualsSequential) {
    Rng rng(6);
    RunningStats a, b, all;
    for (int i = 0; i < 1000; ++i) {
        double x = rng.uniformDouble() * 3 - 1;
        (i % 3 ? a : b).add(x);
        all.add(x);
    }
    a.merge(b);
    EXPECT_EQ(a.count(), all.count());
    EXPECT_NEAR(a.mean(), all.mean(), 1e-12);
    EXPECT_NEAR(a.variance(), all.variance(), 1e-12);
}

// The sample variance is unbiased: averaged over many independent runs of n = 5 samples
// it equals the true variance (1/12 for a uniform variable) within 4 standard errors.
TEST(RunningStats, SampleVarianceIsUnbiased) {
    Rng rng(7);
    RunningStats ofVariances;
    for (int run = 0; run < 20000; ++run) {
        RunningStats s;
        for (int i = 0; i < 5; ++i) s.add(rng.uniformDouble());
        ofVariances.add(s.variance());
    }
    EXPECT_NEAR(ofVariances.mean(), 1.0 / 12, 4 * ofVariances.standardError());
}

TEST(Estimator, EfficiencyAndMse) {
    EXPECT_DOUBLE_EQ(efficiency(0.5, 4), 0.5);
    EXPECT_DOUBLE_EQ(efficiency(0, 4), 0);
    EXPECT_DOUBLE_EQ(meanSquaredError(0.25, 0.5), 0.5);
}
