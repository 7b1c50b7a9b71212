// The MIS heuristics of thesis ch. 9 (mc/mis.h): for random sets of densities, the weights
// of every heuristic sum to one over the techniques that can produce the point (eq. 9.4's
// condition for an unbiased combination); the --mis syntax; and the glossy-highlight study
// (mc/mis_study.h): exact integral, every strategy unbiased, and the ranking of §9.2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "mc/mis.h"
#include "mc/mis_study.h"
#include "mc/rng.h"
#include "util/error.h"

using namespace ps;

namespace {

std::vector<MisWeighting> everyHeuristic() {
    std::vector<MisWeighting> all;
    for (const char* s : {"balance", "power", "power:1", "power:3", "power:0.5", "power:8", "cutoff", "cutoff:0",
                          "cutoff:0.5", "cutoff:1", "maximum", "none"})
        all.push_back(parseMisWeighting(s));
    return all;
}

}  // namespace

TEST(Mis, WeightsSumToOneForRandomDensities) {
    Rng rng(11);
    int sets = 0;
    for (const MisWeighting& h : everyHeuristic()) {
        SCOPED_TRACE(misWeightingName(h));
        for (int trial = 0; trial < 2000; ++trial) {
            const int n = 2 + int(rng.uniform() * 7);  // 2..8 techniques
            std::vector<double> p(static_cast<size_t>(n), 0.0);
            for (double& x : p) {
                // Densities over many decades, some techniques unable to sample the point
                // (0), and some exactly tied (the maximum heuristic shares them).
                const float u = rng.uniform();
                x = u < 0.15f ? 0.0 : u < 0.25f ? 1.0 : std::exp(20 * (rng.uniform() - 0.5));
            }
            if (trial % 5 == 0) p[1] = p[0];
            double sum = 0;
            bool any = false;
            for (int i = 0; i < n; ++i) {
                std::vector<double> others;
                for (int j = 0; j < n; ++j)
                    if (j != i) others.push_back(p[size_t(j)]);
                const double w = h.weight(p[size_t(i)], others.data(), int(others.size()));
                EXPECT_GE(w, 0);
                EXPECT_LE(w, 1 + 1e-12);
                if (p[size_t(i)] == 0) {
                    EXPECT_EQ(w, 0);
                }
                sum += w;
                any |= p[size_t(i)] > 0;
            }
            if (any) {
                EXPECT_NEAR(sum, 1.0, 1e-9) << "n " << n;
            }
            ++sets;
        }
    }
    std::printf("  %d density sets checked\n", sets);
}

// Where techniques sample alike (a diffuse furnace: light and cosine sampling have equal
// densities), each technique's evaluation of the densities differs from the others' by
// rounding; the weights must still sum to one. Here every technique sees every density
// with its own relative error of up to 1e-6 (floats give about 1e-7), several densities
// being equal before it.
TEST(Mis, WeightsSumToOneWhenEqualDensitiesDifferByRounding) {
    Rng rng(5);
    for (const MisWeighting& h : everyHeuristic()) {
        SCOPED_TRACE(misWeightingName(h));
        for (int trial = 0; trial < 2000; ++trial) {
            const int n = 2 + int(rng.uniform() * 5);
            std::vector<double> p(static_cast<size_t>(n), 0.0);
            const double common = std::exp(10 * (rng.uniform() - 0.5));
            for (double& x : p) x = rng.uniform() < 0.6f ? common : common * std::exp(4 * (rng.uniform() - 0.5));
            double sum = 0;
            for (int i = 0; i < n; ++i) {
                auto seen = [&](double x) { return x * (1 + 1e-6 * (2 * rng.uniformDouble() - 1)); };
                std::vector<double> others;
                for (int j = 0; j < n; ++j)
                    if (j != i) others.push_back(seen(p[size_t(j)]));
                sum += h.weight(seen(p[size_t(i)]), others.data(), int(others.size()));
            }
            EXPECT_NEAR(sum, 1.0, 1e-5) << "n " << n;
        }
    }
}

// The heuristics' defining values (§9.2.2, §9.2.4) on two techniques.
TEST(Mis, HeuristicsTakeTheirDefiningValues) {
    EXPECT_NEAR(parseMisWeighting("balance").weight(3, 1), 0.75, 1e-12);
    EXPECT_NEAR(parseMisWeighting("power").weight(3, 1), 0.9, 1e-12);
    EXPECT_NEAR(parseMisWeighting("power:3").weight(3, 1), 27.0 / 28, 1e-12);
    EXPECT_NEAR(parseMisWeighting("power").weight(3, 1), powerHeuristic(3, 1), 1e-7);
    EXPECT_NEAR(parseMisWeighting("maximum").weight(3, 1), 1, 0);
    EXPECT_NEAR(parseMisWeighting("maximum").weight(1, 3), 0, 0);
    EXPECT_NEAR(parseMisWeighting("maximum").weight(2, 2), 0.5, 0);
    // Cutoff 0.5: 1 < 0.5 * 3 drops out, the other takes everything; 2 vs 3 balanced.
    EXPECT_NEAR(parseMisWeighting("cutoff:0.5").weight(1, 3), 0, 0);
    EXPECT_NEAR(parseMisWeighting("cutoff:0.5").weight(3, 1), 1, 0);
    EXPECT_NEAR(parseMisWeighting("cutoff:0.5").weight(2, 3), 0.4, 1e-12);
    EXPECT_NEAR(parseMisWeighting("none").weight(5, 1), 0.5, 0);
    EXPECT_NEAR(parseMisWeighting("none").weight(5, 0), 1, 0);
}

TEST(Mis, Syntax) {
    EXPECT_TRUE(parseMisWeighting("power").isDefault());
    EXPECT_TRUE(parseMisWeighting("power:2").isDefault());
    EXPECT_EQ(parseMisWeighting("power:3").beta, 3);
    EXPECT_EQ(parseMisWeighting("cutoff").alpha, 0.1f);
    EXPECT_EQ(parseMisWeighting("cutoff:0.25").alpha, 0.25f);
    for (const char* s : {"balance", "power", "power:3", "power:0.5", "cutoff:0.1", "cutoff:0.25", "maximum", "none"})
        EXPECT_EQ(misWeightingName(parseMisWeighting(s)), s);
    EXPECT_EQ(misWeightingName(parseMisWeighting("power:2")), "power");
    EXPECT_EQ(misWeightingName(parseMisWeighting("cutoff")), "cutoff:0.1");
    for (const char* bad : {"", "max", "power:", "power:0", "power:-1", "power:x", "power:inf", "cutoff:1.5",
                            "cutoff:-0.1", "balance:2", "maximum:1", "none:0", "Power"})
        EXPECT_THROW(parseMisWeighting(bad), InputError) << bad;
}

// The glossy highlight's quadrature against a case with a closed form: the light centred on
// the mirror direction gets 1 - cos^(n+1)(r) of the lobe.
TEST(MisStudy, ExactIntegralAgreesWithTheClosedForm) {
    for (double n : {10.0, 1000.0})
        for (double r : {0.01, 0.3}) {
            GlossyHighlight g{r, 0, n};
            EXPECT_NEAR(g.exact(), 1 - std::pow(std::cos(r), n + 1), 1e-6 * (1 - std::pow(std::cos(r), n + 1)))
                << n << " " << r;
        }
}

// Every strategy of the study estimates the integral (within 4 sigma in every case, plus
// the lobe's tail outside the largest light, which 40,000 BSDF samples rarely meet), and the
// variances rank as ch. 9 says: each technique alone fails badly somewhere; the balance
// heuristic never exceeds the best variance by more than I^2 / 2 (Theorem 9.2, one sample
// per technique), nor does power; power beats balance where one technique is nearly exact
// (the low-variance cases §9.2.4 improves), and maximum loses to balance where the two
// densities are comparable.
TEST(MisStudy, StrategiesAreUnbiasedAndRankAsChapter9Says) {
    const std::vector<MisStrategy> st = misStudyStrategies();
    ASSERT_EQ(st.size(), 6u);  // balance, power:2, cutoff:0.1, maximum, light alone, bsdf alone
    const int samples = 40000;
    const std::vector<MisStudyCell> cells = runMisStudy(st, samples, 3);
    ASSERT_EQ(cells.size(), 16u);
    std::vector<double> excess(st.size(), 0);
    int powerBetter = 0, maximumWorse = 0;
    for (const MisStudyCell& c : cells) {
        const double best = *std::min_element(c.variance.begin(), c.variance.end());
        for (size_t i = 0; i < st.size(); ++i) {
            const double sigma = std::sqrt(c.variance[i] / samples);
            EXPECT_NEAR(c.mean[i], c.exact, 4 * sigma + 1e-6 * c.exact)
                << st[i].name << " r " << c.setup.lightRadius << " n " << c.setup.exponent;
            excess[i] = std::max(excess[i], (c.variance[i] - best) / (c.exact * c.exact));
        }
        powerBetter += c.variance[1] < c.variance[0];
        maximumWorse += c.variance[3] > 2 * c.variance[0];
    }
    for (size_t i = 0; i < st.size(); ++i)
        std::printf("  %-12s largest (V - V_best) / I^2 %.3g\n", st[i].name.c_str(), excess[i]);
    std::printf("  power below balance in %d cases, maximum over 2x balance in %d\n", powerBetter, maximumWorse);
    EXPECT_GT(excess[4], 10);  // light sampling alone, on sharp lobes under large lights
    EXPECT_GT(excess[5], 10);  // BSDF sampling alone, on rough lobes under small lights
    EXPECT_LE(excess[0], 0.5);  // balance: Theorem 9.2
    EXPECT_LE(excess[1], 0.5);  // power
    EXPECT_GE(powerBetter, 12);
    EXPECT_GE(maximumWorse, 1);
}
