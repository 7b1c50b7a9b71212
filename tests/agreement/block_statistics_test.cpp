// The comparison the agreement matrix and `pathspace verify` make, on synthetic renders whose
// truth is known: it must pass unbiased estimators and catch a small bias.
#include <gtest/gtest.h>

#include <cmath>

#include "mc/rng.h"
#include "verify/block_statistics.h"

namespace ps::verify {
namespace {

TEST(BlockStatistics, StudentTails) {
    EXPECT_NEAR(studentTwoSidedTail(2.365, 7), 0.05, 2e-4);   // the t table's 97.5% point
    EXPECT_NEAR(studentTwoSidedTail(2.131, 15), 0.05, 2e-4);
    EXPECT_NEAR(studentTwoSidedTail(1.96, 1e9), 0.05, 1e-4);  // the normal limit
    EXPECT_NEAR(fourSigmaEquivalent(1e9), 4.0, 1e-3);
    EXPECT_GT(fourSigmaEquivalent(7), 8.0);  // heavier tails: far wider at 8 renders
    EXPECT_NEAR(chiSquareUpperQuantile(16, 0.01), 32.0, 0.2);
}

// K renders of a 16 x 16 image whose every pixel is `mean` times (1 + noise).
RunSet noisyRuns(double mean, double noise, int runs, uint64_t seed) {
    RunSet r(4, 4);
    Rng rng(seed);
    for (int k = 0; k < runs; ++k) {
        Image img(16, 16);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                // A sum of uniforms: roughly normal, unit variance.
                double g = 0;
                for (int i = 0; i < 12; ++i) g += rng.uniformDouble();
                img.set(x, y, Spectrum(float(mean * (1 + noise * (g - 6)))));
            }
        r.add(img);
    }
    return r;
}

TEST(BlockStatistics, PassesUnbiasedAndCatchesABias) {
    int falseAlarms = 0, caught = 0;
    for (uint64_t s = 0; s < 50; ++s) {
        const RunSet a = noisyRuns(1.0, 0.05, 16, 2 * s + 1), b = noisyRuns(1.0, 0.05, 16, 2 * s + 2);
        const RunSet biased = noisyRuns(1.02, 0.05, 16, 2 * s + 2);
        const Verdict same = compare(a, referenceFrom(b, "b"));
        EXPECT_LT(same.resolution, 0.02);
        falseAlarms += !same.agrees;
        caught += !compare(biased, referenceFrom(a, "a")).agrees;
    }
    EXPECT_EQ(falseAlarms, 0);
    EXPECT_EQ(caught, 50);
    // An exact reference: a bias of 1% in every pixel.
    EXPECT_FALSE(compare(noisyRuns(1.01, 0.02, 16, 7), exactReference(1.0, 16)).agrees);
    EXPECT_TRUE(compare(noisyRuns(1.0, 0.02, 16, 7), exactReference(1.0, 16)).agrees);
}

TEST(BlockStatistics, PooledReferenceWeighsByPrecision) {
    const RunSet precise = noisyRuns(1.0, 0.01, 16, 1), noisy = noisyRuns(1.0, 0.2, 16, 2);
    const Reference r = pooledOf({&precise, &noisy}, "pooled");
    EXPECT_LT(r.image.stdErr, precise.image().stdErr);
    EXPECT_NEAR(r.image.mean, precise.image().mean, 2 * precise.image().stdErr);
    EXPECT_EQ(r.dof, 30);
    EXPECT_FALSE(compare(noisyRuns(1.03, 0.01, 16, 3), r).agrees);
}

}  // namespace
}  // namespace ps::verify
