// Every estimator is unbiased: the mean of many independent runs lies within 4 standard
// errors (of that mean) of the exact integral. Integrands with finite variance only.
#include <gtest/gtest.h>

#include <cstdio>

#include "mc/control_variates.h"
#include "mc/techniques.h"
#include "mc/test_integrands.h"
#include "mc_test_util.h"

using namespace ps;
using namespace ps::test;

TEST(Estimators, EveryTechniqueIsUnbiased) {
    const int runs = 400, n = 256;
    for (const char* name : {"exp", "halfspace", "ball"}) {
        for (int dims : {1, 3}) {
            TestIntegrand t = makeTestIntegrand(name, dims);
            for (const Technique& tech : techniques()) {
                if (!tech.applies(t)) continue;
                RunsSummary s = repeatRuns([&](Rng& rng) { return tech.run(t, n, rng); }, runs,
                                           hashCombine(dims, std::hash<std::string>{}(tech.name + name)));
                double sig = sigmasFrom(s.estimates, t.exact);
                if (sig > 2.5)
                    std::printf("[ unbiased ] %-9s s=%d %-11s %.2f sigma\n", name, dims, tech.name.c_str(), sig);
                EXPECT_LT(sig, 4.0) << tech.name << " on " << name << " s=" << dims << ": mean "
                                    << s.estimates.mean() << " exact " << t.exact;
            }
        }
    }
}

TEST(Estimators, ReportedStandardErrorMatchesTheSpreadForIndependentSamples) {
    // The runs' own error estimates are right for the i.i.d.-based estimators (the spread of
    // the estimates over runs is the truth). Stratified/QMC are excluded: theirs is conservative.
    TestIntegrand t = makeTestIntegrand("exp", 3);
    for (const char* name : {"independent", "antithetic", "control", "regression", "expected", "importance",
                             "roulette", "splitting", "two-stage"}) {
        const Technique& tech = *findTechnique(name);
        RunsSummary s = repeatRuns([&](Rng& rng) { return tech.run(t, 1024, rng); }, 400, 77);
        double ratio = s.meanReportedVariance / s.estimates.variance();
        // The variance of a 400-run sample variance is about 2/399 relative: 4 sigma is 28%.
        EXPECT_NEAR(ratio, 1.0, 0.3) << name;
    }
}

TEST(Estimators, FixedCoefficientControlVariateIsUnbiasedForAnyBeta) {
    TestIntegrand t = makeTestIntegrand("gaussian", 2);
    ControlFunction g{[](std::span<const double> u) { return u[0] * u[1]; }, 0.25};
    for (double beta : {-2.0, 0.0, 1.0, 3.0}) {
        RunsSummary s = repeatRuns(
            [&](Rng& rng) {
                return estimateControlVariate(t.f, g, beta, generatePoints(PointSetKind::Independent, 128, 2, rng));
            },
            400, 5);
        EXPECT_LT(sigmasFrom(s.estimates, t.exact), 4.0) << "beta " << beta;
    }
}
