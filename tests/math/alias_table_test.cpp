// The alias table must give each outcome exactly its probability: u swept over a fine grid
// of [0,1) lands on each outcome for a fraction of the grid equal to its pmf, and outcomes
// of weight 0 (or negative, or NaN) are never drawn.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mc/alias_table.h"

namespace ps {
namespace {

std::vector<double> sweep(const AliasTable& t, int steps) {
    std::vector<double> freq(size_t(t.size()), 0.0);
    for (int k = 0; k < steps; ++k) freq[size_t(t.sample((float(k) + 0.5f) / float(steps)))] += 1.0 / steps;
    return freq;
}

TEST(AliasTable, FrequenciesMatchWeights) {
    const std::vector<std::vector<float>> cases = {
        {1},
        {1, 1},
        {3, 1},
        {0.2f, 5, 0, 1.5f, 0.01f, 7, 0.3f},
        {1e-6f, 1, 1e6f},
        {0, 0, 2, -1, NAN, 1},
    };
    for (const std::vector<float>& w : cases) {
        AliasTable t(w);
        double sum = 0;
        for (float x : w) sum += (std::isfinite(x) && x > 0) ? x : 0;
        std::vector<double> f = sweep(t, 1 << 20);
        for (size_t i = 0; i < w.size(); ++i) {
            double expected = (std::isfinite(w[i]) && w[i] > 0) ? w[i] / sum : 0.0;
            EXPECT_NEAR(t.pmf(int(i)), expected, 1e-6 * std::max(1.0, expected)) << i;
            EXPECT_NEAR(f[i], expected, 2e-5) << "outcome " << i << " of " << w.size();
            if (expected == 0) {
                EXPECT_EQ(f[i], 0.0) << i;
            }
        }
    }
}

TEST(AliasTable, AllZeroIsUniformAndEdgesStayInRange) {
    AliasTable t(std::vector<float>{0, 0, 0, 0});
    for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(t.pmf(i), 0.25f);
    AliasTable u(std::vector<float>{1, 2, 3});
    for (float x : {0.0f, 0x1.fffffep-1f}) {
        int i = u.sample(x);
        EXPECT_GE(i, 0);
        EXPECT_LT(i, 3);
    }
}

}  // namespace
}  // namespace ps
