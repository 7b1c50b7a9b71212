// A primary-sample chain's first iteration as sample i of n (stratifyFirstIteration, the
// Metropolis bootstraps'): the n samples are stratified pair by pair, each is still uniform on
// its own (what keeps b and the chains' start unbiased), the same arguments give the same
// values (a chain's start replays its bootstrap sample), and later iterations are untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mc/primary_sample_sampler.h"

namespace ps {
namespace {

PrimarySampleParams params(int streams) {
    PrimarySampleParams p;
    p.streamCount = streams;
    return p;
}

constexpr int kValues = PrimarySampleSampler::kStratifiedValues;

// The first iteration's values of sample i of n, stream-major, kValues each (read in an
// order other than the streams' to show that the order does not matter).
std::vector<double> sampleValues(uint64_t key, int64_t i, int64_t n, int streams = 3) {
    PrimarySampleSampler sampler(1234 + uint64_t(i), params(streams));
    sampler.startIteration();
    sampler.stratifyFirstIteration(key, i, n);
    std::vector<double> out(size_t(streams * kValues));
    for (int s = streams - 1; s >= 0; --s) {
        sampler.startStream(s);
        for (int k = 0; k < kValues; ++k) out[size_t(s * kValues + k)] = sampler.get1D();
    }
    return out;
}

TEST(BootstrapStrata, EachPairOfValuesIsStratifiedOverTheGroup) {
    // 64 samples: every pair of every stream puts one sample in each cell of an 8 x 8 grid
    // (a (0,6,2)-net, Owen-scrambled), and one in each 1/64 of either axis.
    constexpr int n = 64, streams = 3;
    std::vector<std::vector<double>> v;
    for (int i = 0; i < n; ++i) v.push_back(sampleValues(7, i, n, streams));
    for (int s = 0; s < streams; ++s)
        for (int pair = 0; pair < kValues / 2; ++pair) {
            const size_t a = size_t(s * kValues + 2 * pair);
            std::vector<int> grid(64, 0), xs(64, 0), ys(64, 0);
            for (const auto& x : v) {
                ++grid[size_t(int(x[a] * 8) * 8 + int(x[a + 1] * 8))];
                ++xs[size_t(x[a] * 64)];
                ++ys[size_t(x[a + 1] * 64)];
            }
            for (int c = 0; c < 64; ++c) {
                EXPECT_EQ(grid[size_t(c)], 1) << "stream " << s << " pair " << pair << " cell " << c;
                EXPECT_EQ(xs[size_t(c)], 1) << "stream " << s << " pair " << pair << " x stratum " << c;
                EXPECT_EQ(ys[size_t(c)], 1) << "stream " << s << " pair " << pair << " y stratum " << c;
            }
        }
}

TEST(BootstrapStrata, DifferentPairsArePairedAtRandom) {
    // Padding: pair 0 and pair 1 of a stream must not be the same points in the same order
    // (then the 4D set would lie on a 2D surface). Their values' correlation over the group
    // is small.
    constexpr int n = 256;
    double sxy = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
    for (int i = 0; i < n; ++i) {
        const std::vector<double> v = sampleValues(11, i, n);
        const double x = v[0], y = v[2];
        sx += x, sy += y, sxy += x * y, sxx += x * x, syy += y * y;
    }
    const double cov = sxy / n - sx / n * sy / n;
    const double r = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
    EXPECT_LT(std::abs(r), 4 / std::sqrt(double(n))) << "pair 0 and pair 1 are correlated: r = " << r;
}

TEST(BootstrapStrata, EverySampleIsUniformOnItsOwn) {
    // Sample 5 of 16 over 4000 seeds: each of its values is uniform (mean 1/2, variance 1/12
    // within 4 sigma; a chi-square over 16 bins under its p = 1e-6 bound).
    constexpr int seeds = 4000, bins = 16;
    std::vector<int> hist(bins, 0);
    double sum = 0, squares = 0;
    for (int seed = 0; seed < seeds; ++seed) {
        const std::vector<double> v = sampleValues(uint64_t(seed) * 7919, 5, 16);
        for (double x : {v[0], v[3], v[kValues + 6]}) {
            ++hist[size_t(x * bins)];
            sum += x;
            squares += x * x;
        }
    }
    const double m = 3.0 * seeds;
    EXPECT_NEAR(sum / m, 0.5, 4 * std::sqrt(1.0 / 12 / m));
    EXPECT_NEAR(squares / m - (sum / m) * (sum / m), 1.0 / 12, 0.01);
    double chi2 = 0;
    for (int b = 0; b < bins; ++b) chi2 += std::pow(hist[size_t(b)] - m / bins, 2) / (m / bins);
    EXPECT_LT(chi2, 53.0);  // 15 degrees of freedom, p = 1e-6
}

TEST(BootstrapStrata, SameArgumentsSameValuesOtherKeysOthers) {
    EXPECT_EQ(sampleValues(3, 9, 100), sampleValues(3, 9, 100));
    EXPECT_NE(sampleValues(3, 9, 100), sampleValues(4, 9, 100));
}

TEST(BootstrapStrata, OnlyTheFirstIterationAndTheFirstValues) {
    // Values past the first kValues, and every value of later large steps, are the chain's own
    // draws: the same as without strata (a stratified value still takes its draw).
    PrimarySampleSampler plain(77, params(1)), strat(77, params(1));
    plain.startIteration();
    strat.startIteration();
    strat.stratifyFirstIteration(5, 3, 10);
    for (int k = 0; k < kValues; ++k) {
        plain.get1D();
        strat.get1D();
    }
    EXPECT_EQ(plain.get1D(), strat.get1D());
    plain.accept();
    strat.accept();
    plain.startIteration(true);
    strat.startIteration(true);
    for (int k = 0; k < kValues; ++k) EXPECT_EQ(plain.get1D(), strat.get1D()) << "value " << k;
}

}  // namespace
}  // namespace ps
