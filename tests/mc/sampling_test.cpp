// Sampling random variables: rejection sampling, Metropolis-Hastings, normal deviates,
// autocorrelation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mc/autocorrelation.h"
#include "mc/metropolis.h"
#include "mc/rejection_sampling.h"

using namespace ps;

namespace {

// Kolmogorov-Smirnov distance between samples and a CDF.
double ksDistance(std::vector<double> xs, const std::function<double(double)>& cdf) {
    std::sort(xs.begin(), xs.end());
    double d = 0, n = double(xs.size());
    for (size_t i = 0; i < xs.size(); ++i) {
        double c = cdf(xs[i]);
        d = std::max({d, std::abs(c - i / n), std::abs((i + 1) / n - c)});
    }
    return d;
}

// KS critical value at level 0.1%: 1.95 / sqrt(n) (asymptotic).
double ksCritical(double n) { return 1.95 / std::sqrt(n); }

}  // namespace

TEST(RejectionSampling, AcceptanceRateIsOneOverMAndSamplesFollowTheTarget) {
    // Target p(x) = 3 x^2 on [0,1), uniform proposals. M = 3 is the tight envelope; M = 6 is loose.
    for (double M : {3.0, 6.0}) {
        RejectionSampler s(
            1, [](std::span<const double> x) { return 3 * x[0] * x[0]; },
            [](Rng& rng, std::span<double> x) { x[0] = rng.uniformDouble(); },
            [](std::span<const double>) { return 1.0; }, M);
        Rng rng(41);
        std::vector<double> xs;
        std::vector<double> x(1);
        for (int i = 0; i < 50000; ++i) {
            ASSERT_TRUE(s.sample(rng, x));
            xs.push_back(x[0]);
        }
        double rate = s.acceptanceRate(), se = std::sqrt((1 / M) * (1 - 1 / M) / double(s.tries()));
        std::printf("[ reject   ] M=%.0f acceptance %.4f (1/M = %.4f)\n", M, rate, 1 / M);
        EXPECT_NEAR(rate, 1 / M, 4 * se);
        EXPECT_EQ(s.envelopeViolations(), 0);
        EXPECT_LT(ksDistance(xs, [](double v) { return v * v * v; }), ksCritical(double(xs.size())));
    }
}

TEST(RejectionSampling, CountsEnvelopeViolations) {
    // M = 1 is too small for 3 x^2: detected rather than silently sampling the wrong density.
    RejectionSampler s(
        1, [](std::span<const double> x) { return 3 * x[0] * x[0]; },
        [](Rng& rng, std::span<double> x) { x[0] = rng.uniformDouble(); }, [](std::span<const double>) { return 1.0; },
        1.0);
    Rng rng(42);
    std::vector<double> x(1);
    for (int i = 0; i < 1000; ++i) s.sample(rng, x);
    EXPECT_GT(s.envelopeViolations(), 0);
}

TEST(Metropolis, RandomWalkChainHasTheTargetDistributionAndFewerEffectiveSamples) {
    // Unnormalised bimodal target on [0,1): f(x) = exp(-(x-0.25)^2/0.005) + 0.5 exp(-(x-0.7)^2/0.01).
    auto f = [](std::span<const double> x) {
        return std::exp(-(x[0] - 0.25) * (x[0] - 0.25) / 0.005) + 0.5 * std::exp(-(x[0] - 0.7) * (x[0] - 0.7) / 0.01);
    };
    // Its CDF by fine numerical integration (the target is smooth).
    const int grid = 20000;
    std::vector<double> cdf(grid + 1, 0.0);
    for (int i = 0; i < grid; ++i) {
        double xm = (i + 0.5) / grid;
        cdf[i + 1] = cdf[i] + f(std::span<const double>(&xm, 1)) / grid;
    }
    for (double& c : cdf) c /= cdf[grid];
    auto cdfAt = [&](double v) {
        double g = v * grid;
        int i = std::min(grid - 1, int(g));
        return cdf[i] + (g - i) * (cdf[i + 1] - cdf[i]);
    };

    RandomWalkProposal walk(0.1, true);
    Rng rng(43);
    std::vector<double> start{0.25};
    MetropolisChain chain = runMetropolis(f, walk, start, 200000, 1000, rng);
    std::vector<double> xs = chain.coordinate(0);
    AutocorrelationSummary ac = integratedAutocorrelation(xs);
    double d = ksDistance(xs, cdfAt);
    std::printf("[ metropolis ] random walk: acceptance %.3f, tau %.2f, ESS %.0f of %zu, KS %.4f (critical %.4f at ESS)\n",
                chain.acceptanceRate(), ac.tau, ac.ess, xs.size(), d, ksCritical(ac.ess));
    EXPECT_GT(chain.acceptanceRate(), 0.2);
    EXPECT_LT(chain.acceptanceRate(), 0.9);
    EXPECT_GT(ac.tau, 2.0);  // correlated: ESS well below N
    EXPECT_LT(ac.ess, 0.5 * double(xs.size()));
    // KS with the effective sample size stands in for the i.i.d. count.
    EXPECT_LT(d, ksCritical(ac.ess));
}

TEST(Metropolis, IndependenceProposalNeedsItsTransitionRatio) {
    // Target 3 x^2, proposals from g(x) = 1/2 + x (sampled by inversion: x = (-1 + sqrt(1 + 8u)) / 2).
    auto f = [](std::span<const double> x) { return x[0] * x[0]; };
    auto gSample = [](Rng& rng, std::span<double> y) { y[0] = (-1 + std::sqrt(1 + 8 * rng.uniformDouble())) / 2; };
    auto gPdf = [](std::span<const double> x) { return 0.5 + x[0]; };
    IndependenceProposal proposal(gSample, gPdf);
    Rng rng(44);
    std::vector<double> start{0.5};
    MetropolisChain chain = runMetropolis(f, proposal, start, 100000, 100, rng);
    std::vector<double> xs = chain.coordinate(0);
    AutocorrelationSummary ac = integratedAutocorrelation(xs);
    double d = ksDistance(xs, [](double v) { return v * v * v; });
    std::printf("[ metropolis ] independence: acceptance %.3f, tau %.2f, KS %.4f (critical %.4f)\n",
                chain.acceptanceRate(), ac.tau, d, ksCritical(ac.ess));
    EXPECT_LT(d, ksCritical(ac.ess));

    // Without the ratio g(x)/g(y) (treating g as symmetric) the chain targets f * g instead:
    // the KS test must see the difference.
    struct Symmetric final : MetropolisProposal {
        IndependenceProposal& inner;
        explicit Symmetric(IndependenceProposal& p) : inner(p) {}
        void propose(std::span<const double> x, std::span<double> y, Rng& r) override { inner.propose(x, y, r); }
        double transitionRatio(std::span<const double>, std::span<const double>) const override { return 1.0; }
    } wrong(proposal);
    MetropolisChain bad = runMetropolis(f, wrong, start, 100000, 100, rng);
    std::vector<double> ys = bad.coordinate(0);
    EXPECT_GT(ksDistance(ys, [](double v) { return v * v * v; }), ksCritical(integratedAutocorrelation(ys).ess));
}

// Box-Muller's pairs: each deviate standard normal (KS, both members of the pairs apart)
// and the two members of a pair uncorrelated (|r| < 4 / sqrt(n)).
TEST(NormalPairs, DeviatesAreStandardNormalAndThePairsIndependent) {
    Rng rng(7, 11);
    NormalPairs normals;
    const int n = 100000;
    std::vector<double> first(n), second(n);
    double sxy = 0;
    for (int i = 0; i < n; ++i) {
        first[size_t(i)] = normals.next(rng);
        second[size_t(i)] = normals.next(rng);
        sxy += first[size_t(i)] * second[size_t(i)];
    }
    auto phi = [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); };
    const double d1 = ksDistance(first, phi), d2 = ksDistance(second, phi), r = sxy / n;
    std::printf("KS %.4f and %.4f (critical %.4f); correlation within pairs %.4f (bound %.4f)\n", d1, d2,
                ksCritical(n), r, 4 / std::sqrt(double(n)));
    EXPECT_LT(d1, ksCritical(n));
    EXPECT_LT(d2, ksCritical(n));
    EXPECT_LT(std::abs(r), 4 / std::sqrt(double(n)));
}

TEST(Autocorrelation, MatchesAnAr1ProcessAndIndependentSamples) {
    // AR(1) x_t = rho x_{t-1} + e_t has tau = (1 + rho) / (1 - rho).
    Rng rng(45);
    for (double rho : {0.0, 0.5, 0.8}) {
        std::vector<double> xs(200000);
        double x = 0;
        for (double& v : xs) v = x = rho * x + standardNormal(rng);
        AutocorrelationSummary ac = integratedAutocorrelation(xs);
        double expected = (1 + rho) / (1 - rho);
        std::printf("[ autocorr ] rho %.1f: tau %.3f (exact %.3f)\n", rho, ac.tau, expected);
        EXPECT_NEAR(ac.tau, expected, 0.1 * expected);
        EXPECT_NEAR(ac.ess, double(xs.size()) / ac.tau, 1e-6 * ac.ess);
    }
}
