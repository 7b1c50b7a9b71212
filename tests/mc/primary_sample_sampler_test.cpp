// The primary-sample-space Metropolis kernel (Kelemen et al. 2002) on its own, before any
// rendering: chains with exactly the small / large steps, lazy catch-up and restore of
// PrimarySampleSampler over targets of known density. A chain's samples are correlated, so
// a per-sample chi-square would overstate its confidence: each cell's sigma is measured
// across independent chains.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "materials/stats.h"
#include "mc/estimator.h"
#include "mc/primary_sample_sampler.h"

namespace ps {
namespace {

// What a target function reports for the sampler's current proposal: its value and the
// histogram cell of the point it read.
struct TargetValue {
    double f = 0;
    int cell = 0;
    size_t kind = ~size_t(0);  // the partial step kind the state takes (startIterationOfKind); default: uniform
};
using Target = std::function<TargetValue(PrimarySampleSampler&)>;

// One chain: every iteration records the current state with weight 1 - a and the proposal
// with weight a (thesis ch. 11, "use of expected values"), or, if !expectedValues, the
// state after the step with weight 1. Returns the fraction of the weight in each cell.
std::vector<double> chainHistogram(const Target& target, int cells, uint64_t seed, const PrimarySampleParams& params,
                                   int burnIn, int iterations, bool expectedValues) {
    PrimarySampleSampler sampler(seed, params);
    sampler.startIteration();
    TargetValue x = target(sampler);
    sampler.accept();
    std::vector<double> hist(size_t(cells), 0.0);
    for (int i = 0; i < burnIn + iterations; ++i) {
        sampler.startIterationOfKind(x.kind);
        TargetValue y = target(sampler);
        double a = acceptanceProbability(x.f, y.f);
        if (i >= burnIn && expectedValues) {
            hist[size_t(x.cell)] += 1 - a;
            hist[size_t(y.cell)] += a;
        }
        if (Rng(mix64(seed ^ uint64_t(i)), 7).uniformDouble() < a) {
            sampler.accept();
            x = y;
        } else {
            sampler.reject();
        }
        if (i >= burnIn && !expectedValues) hist[size_t(x.cell)] += 1;
    }
    for (double& h : hist) h /= iterations;
    return hist;
}

// Each cell's mean fraction over `chains` independent chains against its exact probability,
// in units of the standard error measured across the chains; the sum of squares is about
// chi-square with cells - 1 degrees of freedom (the fractions sum to 1).
test::ChiSquareResult acrossChains(const Target& target, const std::vector<double>& exact, int chains, uint64_t seed,
                                   const PrimarySampleParams& params, int iterations, bool expectedValues,
                                   const char* label) {
    std::vector<RunningStats> cell(exact.size());
    for (int c = 0; c < chains; ++c) {
        std::vector<double> h = chainHistogram(target, int(exact.size()), hashCombine(seed, uint64_t(c)), params, 200,
                                               iterations, expectedValues);
        for (size_t b = 0; b < h.size(); ++b) cell[b].add(h[b]);
    }
    test::ChiSquareResult r;
    double worst = 0;
    std::vector<double> relativeSigma;
    for (size_t b = 0; b < exact.size(); ++b) {
        relativeSigma.push_back(cell[b].standardError() / exact[b]);
        double z = (cell[b].mean() - exact[b]) / cell[b].standardError();
        r.chi2 += z * z;
        worst = std::max(worst, std::fabs(z));
    }
    r.dof = int(exact.size()) - 1;
    r.pValue = test::chiSquarePValue(r.chi2, r.dof);
    std::nth_element(relativeSigma.begin(), relativeSigma.begin() + relativeSigma.size() / 2, relativeSigma.end());
    std::printf("[ kernel   ] %-34s chi2 %.1f (%d dof), p = %.3g, worst cell %.2f sigma, median cell sigma %.2f%%\n",
                label, r.chi2, r.dof, r.pValue, worst, 100 * relativeSigma[relativeSigma.size() / 2]);
    return r;
}

// Integral of g over [a, b) by the midpoint rule (smooth integrands, 1e-9 accurate).
double integrate(const std::function<double(double)>& g, double a, double b, int n = 20000) {
    double h = (b - a) / n, sum = 0;
    for (int i = 0; i < n; ++i) sum += g(a + (i + 0.5) * h);
    return sum * h;
}

// A 1-D density with a bump at the wrap-around point 0 = 1, where a step that clamped
// instead of wrapping would no longer be symmetric.
double bumpy(double u) {
    auto bump = [](double u, double c, double w) { return std::exp(-((u - c) / w) * ((u - c) / w)); };
    return 0.2 + 0.8 * bump(u, 0.02, 0.03) + bump(u, 0.3, 0.05) + 0.5 * bump(u, 0.75, 0.08);
}

constexpr int kBins1D = 20;

std::vector<double> exactBins1D() {
    std::vector<double> p(kBins1D);
    double total = integrate(bumpy, 0, 1, 200000);
    for (int b = 0; b < kBins1D; ++b) p[size_t(b)] = integrate(bumpy, double(b) / kBins1D, double(b + 1) / kBins1D) / total;
    return p;
}

TargetValue bumpyTarget(PrimarySampleSampler& s) {
    float u = s.get1D();
    return {bumpy(u), std::min(int(u * kBins1D), kBins1D - 1)};
}

TEST(PrimarySampleChain, ReproducesOneDimensionalDensity) {
    const std::vector<double> exact = exactBins1D();
    PrimarySampleParams params;  // sigma 0.01, large steps 0.3
    // Both recordings: the chain's states, and the expected values that MLT splats.
    EXPECT_GT(acrossChains(bumpyTarget, exact, 64, 11, params, 20000, false, "1-D, states").pValue, 1e-5);
    EXPECT_GT(acrossChains(bumpyTarget, exact, 64, 12, params, 20000, true, "1-D, expected values").pValue, 1e-5);
    // Small steps only: the chain must cross the whole interval by random walk (and wrap).
    params.largeStepProbability = 0;
    params.sigma = 0.05;
    EXPECT_GT(acrossChains(bumpyTarget, exact, 64, 13, params, 20000, true, "1-D, small steps only").pValue, 1e-5);
}

// A 2-D target whose second coordinate is read only where u0 >= 0.4: there f = h(u0) k(u1),
// elsewhere f = g(u0) and u1 is not part of the path. A chain that spends a while at
// u0 < 0.4 comes back with u1 caught up on the steps it missed, or drawn afresh if a large
// step was accepted meanwhile; a proposal that reads u1 for the first time and is rejected
// must not leave its (conditioned) value behind.
double gLeft(double u0) { return 1 + 2 * u0; }
double hRight(double) { return 0.9; }
double kUp(double u1) { return 0.3 + 2 * std::exp(-((u1 - 0.6) / 0.1) * ((u1 - 0.6) / 0.1)); }

constexpr int kLeftBins = 4, kRightBins0 = 6, kRightBins1 = 8;

TargetValue splitTarget(PrimarySampleSampler& s) {
    float u0 = s.get1D();
    if (u0 < 0.4f) return {gLeft(u0), std::min(int(u0 * 10), kLeftBins - 1)};
    float u1 = s.get1D();
    int i0 = std::min(int((u0 - 0.4f) * 10), kRightBins0 - 1), i1 = std::min(int(u1 * kRightBins1), kRightBins1 - 1);
    return {hRight(u0) * kUp(u1), kLeftBins + i0 * kRightBins1 + i1};
}

std::vector<double> exactSplitBins() {
    std::vector<double> p;
    for (int b = 0; b < kLeftBins; ++b) p.push_back(integrate(gLeft, b * 0.1, (b + 1) * 0.1));
    for (int i0 = 0; i0 < kRightBins0; ++i0)
        for (int i1 = 0; i1 < kRightBins1; ++i1)
            p.push_back(integrate(hRight, 0.4 + i0 * 0.1, 0.5 + i0 * 0.1) *
                        integrate(kUp, double(i1) / kRightBins1, double(i1 + 1) / kRightBins1));
    double total = 0;
    for (double v : p) total += v;
    for (double& v : p) v /= total;
    return p;
}

TEST(PrimarySampleChain, ReproducesTwoDimensionalDensityWithConditionalReads) {
    const std::vector<double> exact = exactSplitBins();
    PrimarySampleParams params;
    EXPECT_GT(acrossChains(splitTarget, exact, 64, 21, params, 20000, true, "2-D conditional, expected values").pValue,
              1e-5);
    params.largeStepProbability = 0.05;  // long stays on either side: many catch-ups
    params.sigma = 0.03;
    EXPECT_GT(acrossChains(splitTarget, exact, 64, 22, params, 20000, false, "2-D conditional, rare large steps").pValue,
              1e-5);
}

// Partial steps (a share of the small steps moves only some streams, each kind with its own
// sigma) keep the target's density: the same 2-D densities with u0 and u1 on two streams,
// one of them read only where u0 >= 0.4, so that u1 catches up across steps that did and did
// not move its stream.
PrimarySampleParams partialParams() {
    PrimarySampleParams params;
    params.streamCount = 2;
    params.largeStepProbability = 0.05;
    params.partialStepProbability = 0.6;
    params.partialSteps = {{1u, 0.03}, {2u, 0.005}};
    return params;
}

TargetValue twoStreamTarget(PrimarySampleSampler& s) {
    s.startStream(1);
    float u1 = s.get1D();
    s.startStream(0);
    float u0 = s.get1D();
    int i0 = std::min(int(u0 * 8), 7), i1 = std::min(int(u1 * 8), 7);
    return {bumpy(u0) * kUp(u1), i0 * 8 + i1};
}

TargetValue splitTwoStreamTarget(PrimarySampleSampler& s) {
    s.startStream(0);
    float u0 = s.get1D();
    if (u0 < 0.4f) return {gLeft(u0), std::min(int(u0 * 10), kLeftBins - 1)};
    s.startStream(1);
    float u1 = s.get1D();
    int i0 = std::min(int((u0 - 0.4f) * 10), kRightBins0 - 1), i1 = std::min(int(u1 * kRightBins1), kRightBins1 - 1);
    return {hRight(u0) * kUp(u1), kLeftBins + i0 * kRightBins1 + i1};
}

TEST(PrimarySampleChain, PartialStepsKeepTheDensity) {
    std::vector<double> exact;
    for (int i0 = 0; i0 < 8; ++i0)
        for (int i1 = 0; i1 < 8; ++i1)
            exact.push_back(integrate(bumpy, i0 / 8.0, (i0 + 1) / 8.0) * integrate(kUp, i1 / 8.0, (i1 + 1) / 8.0));
    double total = 0;
    for (double v : exact) total += v;
    for (double& v : exact) v /= total;
    EXPECT_GT(acrossChains(twoStreamTarget, exact, 64, 71, partialParams(), 20000, true, "2 streams, partial steps").pValue,
              1e-5);
    EXPECT_GT(acrossChains(splitTwoStreamTarget, exactSplitBins(), 64, 72, partialParams(), 20000, false,
                           "2-D conditional, partial steps")
                  .pValue,
              1e-5);
}

// Partial step kinds chosen by the state (as mmlt's light-tracing states take light steps):
// a third stream's value c decides the class, and the class the kind, class A moving stream
// 0 only and class B stream 1 only. No partial step moves c, so each class has a symmetric
// kernel and the chance of a partial step is the same in both: the density is kept.
TargetValue classedTarget(PrimarySampleSampler& s) {
    s.startStream(2);
    const float c = s.get1D();
    s.startStream(0);
    const float u0 = s.get1D();
    s.startStream(1);
    const float u1 = s.get1D();
    const int k = c < 0.5f ? 0 : 1, i0 = std::min(int(u0 * 4), 3), i1 = std::min(int(u1 * 4), 3);
    return {(k == 0 ? 1.0 : 2.0) * bumpy(u0) * kUp(u1), (k * 4 + i0) * 4 + i1, size_t(k)};
}

TEST(PrimarySampleChain, PartialStepKindsChosenByTheStateKeepTheDensity) {
    std::vector<double> exact;
    for (int k = 0; k < 2; ++k)
        for (int i0 = 0; i0 < 4; ++i0)
            for (int i1 = 0; i1 < 4; ++i1)
                exact.push_back((k == 0 ? 1.0 : 2.0) * integrate(bumpy, i0 / 4.0, (i0 + 1) / 4.0) *
                                integrate(kUp, i1 / 4.0, (i1 + 1) / 4.0));
    double total = 0;
    for (double v : exact) total += v;
    for (double& v : exact) v /= total;
    PrimarySampleParams params;
    params.streamCount = 3;
    params.largeStepProbability = 0.05;
    params.partialStepProbability = 0.6;
    params.partialSteps = {{1u, 0.03}, {2u, 0.03}};
    EXPECT_GT(acrossChains(classedTarget, exact, 64, 73, params, 20000, true, "kinds chosen by the state").pValue, 1e-5);
}

// With large steps only, the proposals are independent uniform points whatever the target
// and the acceptances: the values of one proposal, and of successive proposals, fill the
// unit square uniformly (samples independent, so Pearson's chi-square applies per sample).
TEST(PrimarySampleChain, LargeStepsOnlyAreIndependentSampling) {
    PrimarySampleParams params;
    params.largeStepProbability = 1;
    PrimarySampleSampler sampler(31, params);
    const int n = 100000, side = 10;
    std::vector<double> within(side * side, 0.0), successive(side * side, 0.0);
    double fx = 0;
    float previous = -1;
    for (int i = 0; i < n; ++i) {
        sampler.startIteration();
        Vec2 u = sampler.get2D();
        double fy = bumpy(u.x) * bumpy(u.y);
        int cx = std::min(int(u.x * side), side - 1), cy = std::min(int(u.y * side), side - 1);
        within[size_t(cx * side + cy)] += 1;
        if (previous >= 0) successive[size_t(std::min(int(previous * side), side - 1) * side + cx)] += 1;
        previous = u.x;
        if (Rng(uint64_t(i), 3).uniformDouble() < acceptanceProbability(fx, fy)) {
            sampler.accept();
            fx = fy;
        } else {
            sampler.reject();
        }
    }
    std::vector<double> expectedWithin(within.size(), double(n) / within.size());
    std::vector<double> expectedSuccessive(successive.size(), double(n - 1) / successive.size());
    test::ChiSquareResult a = test::chiSquare(within, expectedWithin);
    test::ChiSquareResult b = test::chiSquare(successive, expectedSuccessive);
    std::printf("[ kernel   ] large steps only: (u0, u1) chi2 %.1f, (u0, next u0) chi2 %.1f (%d dof): p = %.3g, %.3g\n",
                a.chi2, b.chi2, a.dof, a.pValue, b.pValue);
    EXPECT_GT(a.pValue, 1e-5);
    EXPECT_GT(b.pValue, 1e-5);
}

// A value not read for n accepted iterations and then read by a small step has moved by
// n + 1 small steps: a normal deviate of variance (n + 1) sigma^2 on the torus. If a large
// step was accepted meanwhile it is a fresh uniform value, independent of the old one.
TEST(PrimarySampleChain, LazyCatchUpIsTheMissedSmallStepsAtOnce) {
    const int missed = 24, samplers = 20000;
    PrimarySampleParams params;  // sigma 0.01
    RunningStats diff2;          // squared displacement on the torus
    std::vector<double> oldNew(64, 0.0);
    for (int k = 0; k < samplers; ++k) {
        for (bool largeBetween : {false, true}) {
            PrimarySampleSampler s(hashCombine(43, uint64_t(2 * k + largeBetween)), params);
            s.startIteration();
            s.get1D();
            double before = s.get1D();  // dimension 1, read once at the start
            s.accept();
            for (int i = 0; i < missed; ++i) {
                s.startIteration(largeBetween && i == missed / 2);
                s.get1D();  // only dimension 0
                s.accept();
            }
            s.startIteration(false);
            s.get1D();
            double after = s.get1D();  // dimension 1: missed + 1 small steps, or fresh
            s.accept();
            if (largeBetween) {
                oldNew[size_t(std::min(int(before * 8), 7) * 8 + std::min(int(after * 8), 7))] += 1;
            } else {
                double d = after - before;
                d -= std::floor(d + 0.5);  // to [-0.5, 0.5)
                diff2.add(d * d);
            }
        }
    }
    double expectedVar = (missed + 1) * params.sigma * params.sigma;
    double z = (diff2.mean() - expectedVar) / diff2.standardError();
    std::vector<double> expected(oldNew.size(), double(samplers) / oldNew.size());
    test::ChiSquareResult fresh = test::chiSquare(oldNew, expected);
    std::printf("[ kernel   ] catch-up over %d steps: variance %.4e, expected %.4e (%.2f sigma); after a large step "
                "(old, new) chi2 %.1f (%d dof), p = %.3g\n",
                missed + 1, diff2.mean(), expectedVar, z, fresh.chi2, fresh.dof, fresh.pValue);
    EXPECT_LT(std::fabs(z), 4.0);
    EXPECT_GT(fresh.pValue, 1e-5);
}

// With partial steps a value catches up on the steps that moved its stream only, each with
// its own variance: read once, then left alone while the other stream is read by steps of
// every kind, its displacement when read again over the variance of the steps its stream
// took (every accepted iteration's, before partial steps existed) has mean 1.
TEST(PrimarySampleChain, LazyCatchUpCountsOnlyTheStepsThatMovedItsStream) {
    PrimarySampleParams params = partialParams();
    params.largeStepProbability = 0;
    RunningStats ratio;
    for (int k = 0; k < 20000; ++k) {
        PrimarySampleSampler s(hashCombine(47, uint64_t(k)), params);
        s.startIteration();
        s.startStream(1);
        const double before = s.get1D();
        s.accept();
        double variance = 0;
        for (int i = 0; i < 24; ++i) {
            s.startIteration();
            s.startStream(0);
            s.get1D();
            if (s.movedStreams() >> 1 & 1u) variance += s.stepSigma() * s.stepSigma();
            s.accept();
        }
        s.startIteration(false);  // every stream: one more step of sigma
        variance += params.sigma * params.sigma;
        s.startStream(1);
        double d = s.get1D() - before;
        d -= std::floor(d + 0.5);
        ratio.add(d * d / variance);
    }
    const double z = (ratio.mean() - 1) / ratio.standardError();
    std::printf("[ kernel   ] partial steps' catch-up: displacement^2 / variance %.4f (%.2f sigma from 1)\n", ratio.mean(), z);
    EXPECT_LT(std::fabs(z), 4.0);
}

// A rejected proposal restores, bit for bit, every value it moved: with a target that reads
// the same values at every state, the whole sampler is as before. A value that the proposal
// first brought up to date (not read by the current state) keeps that up-to-date value,
// stamped with the last accepted iteration: the state it stood for all along.
TEST(PrimarySampleChain, RejectionRestoresTheStateBitIdentically) {
    for (bool partial : {false, true}) {
        PrimarySampleParams params;
        params.streamCount = 3;
        if (partial) {
            params.partialStepProbability = 0.5;
            params.partialSteps = {{1u, 0.02}, {6u, 0.01}};
        }
        PrimarySampleSampler s(51, params);
        auto target = [](PrimarySampleSampler& smp) {
            double f = 1;
            for (int stream = 2; stream >= 0; --stream) {
                smp.startStream(stream);
                for (int i = 0; i < 3; ++i) f *= 0.1 + bumpy(smp.get1D());
            }
            return f;
        };
        s.startIteration();
        double fx = target(s);
        s.accept();
        int rejectedSmall = 0, rejectedLarge = 0;
        for (int i = 0; i < 2000; ++i) {
            const PrimarySampleSampler before = s;
            s.startIteration();
            double fy = target(s);
            if (Rng(uint64_t(i), 5).uniformDouble() < acceptanceProbability(fx, fy)) {
                s.accept();
                fx = fy;
                continue;
            }
            bool large = s.largeStep();
            s.reject();
            ASSERT_TRUE(s.sameState(before)) << "iteration " << i;
            ++(large ? rejectedLarge : rejectedSmall);
        }
        std::printf("[ kernel   ] restored exactly after %d rejected small and %d rejected large steps%s\n", rejectedSmall,
                    rejectedLarge, partial ? " (partial steps)" : "");
        EXPECT_GT(rejectedSmall, 100);
        EXPECT_GT(rejectedLarge, 100);
    }

    // Conditional reads: every value the state had read is restored bit for bit.
    PrimarySampleSampler c(52, PrimarySampleParams{});
    c.startIteration();
    double cx = splitTarget(c).f;
    c.accept();
    int caughtUp = 0;
    for (int i = 0; i < 5000; ++i) {
        const PrimarySampleSampler before = c;
        c.startIteration();
        double cy = splitTarget(c).f;
        if (Rng(uint64_t(i), 6).uniformDouble() < acceptanceProbability(cx, cy)) {
            c.accept();
            cx = cy;
            continue;
        }
        c.reject();
        const auto &b = before.values(), &a = c.values();  // c has one stream
        for (size_t d = 0; d < a.size(); ++d) {
            if (d < b.size() && b[d].modified == c.acceptedIterations()) {
                ASSERT_EQ(a[d].value, b[d].value);
                ASSERT_EQ(a[d].modified, b[d].modified);
            } else if (d >= b.size() || a[d].value != b[d].value || a[d].modified != b[d].modified) {
                ASSERT_EQ(a[d].modified, c.acceptedIterations());
                ++caughtUp;
            }
        }
    }
    EXPECT_GT(caughtUp, 50);
}

// The same seed and the same reads give the same values: a bootstrap sample replays.
TEST(PrimarySampleChain, ReplayIsBitIdentical) {
    PrimarySampleParams params;
    params.streamCount = 2;
    auto run = [&](uint64_t seed) {
        PrimarySampleSampler s(seed, params);
        std::vector<float> read;
        for (int i = 0; i < 50; ++i) {
            s.startIteration();
            for (int stream : {1, 0}) {
                s.startStream(stream);
                for (int j = 0; j < 4; ++j) read.push_back(s.get1D());
            }
            (i % 3 ? static_cast<void>(s.accept()) : s.reject());
        }
        return read;
    };
    EXPECT_EQ(run(61), run(61));
    EXPECT_NE(run(61), run(62));
}

TEST(PrimarySampleChain, InvalidProposalsAreNeverAccepted) {
    EXPECT_EQ(acceptanceProbability(1, 0), 0);
    EXPECT_EQ(acceptanceProbability(1, -2), 0);
    EXPECT_EQ(acceptanceProbability(1, std::nan("")), 0);
    EXPECT_EQ(acceptanceProbability(1, INFINITY), 0);
    EXPECT_EQ(acceptanceProbability(2, 1), 0.5);
    EXPECT_EQ(acceptanceProbability(1, 3), 1);
    EXPECT_EQ(acceptanceProbability(0, 3), 1);  // a state of no value is left for any valid one
}

}  // namespace
}  // namespace ps
