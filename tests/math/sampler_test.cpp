#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "mc/sampler.h"

using namespace ps;

// The published Sobol points (Joe-Kuo direction numbers, generated in Gray-code order)
// start (0,0) (1/2,1/2) (3/4,1/4) (1/4,3/4) (3/8,3/8) (7/8,7/8) (5/8,1/8) (1/8,5/8).
TEST(Sobol, FirstPointsMatchPublishedSequence) {
    const double x[8] = {0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125};
    const double y[8] = {0, 0.5, 0.25, 0.75, 0.375, 0.875, 0.125, 0.625};
    for (uint32_t i = 0; i < 8; ++i) {
        uint32_t gray = i ^ (i >> 1);
        EXPECT_DOUBLE_EQ(sobolDim0(gray) * 0x1p-32, x[i]) << i;
        EXPECT_DOUBLE_EQ(sobolDim1(gray) * 0x1p-32, y[i]) << i;
    }
}

// Every elementary interval of volume 1/N (2^a x 2^b boxes, a + b = m) holds exactly one
// of N = 2^m points: the (0,m,2)-net property, which Owen scrambling preserves.
TEST(Sobol, ScrambledPointsFormA02Net) {
    for (int m : {4, 6, 8}) {
        int n = 1 << m;
        for (uint32_t seed : {1u, 12345u, 0xdeadbeefu}) {
            std::vector<uint32_t> xs(n), ys(n);
            for (int i = 0; i < n; ++i) {
                xs[i] = owenScramble(sobolDim0(i), seed);
                ys[i] = owenScramble(sobolDim1(i), seed * 2654435761u);
            }
            for (int a = 0; a <= m; ++a) {
                int b = m - a;
                std::set<uint64_t> cells;
                for (int i = 0; i < n; ++i) {
                    uint64_t cx = a == 0 ? 0 : xs[i] >> (32 - a), cy = b == 0 ? 0 : ys[i] >> (32 - b);
                    cells.insert((cx << 32) | cy);
                }
                EXPECT_EQ(int(cells.size()), n) << "m=" << m << " a=" << a << " seed=" << seed;
            }
        }
    }
}

// The word-wide transform equals the generator-matrix product, column by column.
TEST(Sobol, ReversedDimension1MatchesGeneratorMatrix) {
    Rng rng(3);
    for (int k = 0; k < 20000; ++k) {
        uint32_t index = k < 1000 ? uint32_t(k) : rng.nextU32(), i = index;
        uint32_t expected = 0, v = 1;
        for (; i; i >>= 1, v ^= v << 1)
            if (i & 1) expected ^= v;
        ASSERT_EQ(sobolDim1Reversed(index), expected) << index;
    }
}

TEST(Sobol, ReversedFormMatches) {
    for (uint32_t i = 0; i < 1000; ++i)
        for (uint32_t seed : {0u, 7u, 0x9e3779b9u}) {
            EXPECT_EQ(owenScrambleReversed(i, seed), owenScramble(sobolDim0(i), seed));
            EXPECT_EQ(owenScrambleReversed(sobolDim1Reversed(i), seed), owenScramble(sobolDim1(i), seed));
        }
}

// Owen scrambling makes each point uniform: the mean of many scrambles of one point is 1/2.
TEST(Sobol, ScrambledPointIsUniform) {
    double sum = 0;
    int n = 100000;
    for (int s = 0; s < n; ++s) sum += fixedToFloat(owenScramble(sobolDim1(5), uint32_t(mix64(s))));
    EXPECT_NEAR(sum / n, 0.5, 4 * std::sqrt(1.0 / 12 / n));
}

TEST(Samplers, DeterministicPerPixelSample) {
    for (const std::string& name : samplerNames()) {
        auto a = createSampler(name, 42), b = createSampler(name, 42);
        a->startPixelSample(3, 4, 5);
        float a1 = a->get1D();
        Vec2 a2 = a->get2D();
        b->startPixelSample(9, 9, 9);
        b->get1D();
        b->startPixelSample(3, 4, 5);
        EXPECT_EQ(b->get1D(), a1) << name;
        Vec2 b2 = b->get2D();
        EXPECT_EQ(b2.x, a2.x) << name;
        EXPECT_EQ(b2.y, a2.y) << name;
    }
    EXPECT_EQ(createSampler("nonsense", 1), nullptr);
}

// Per pixel, the padded Sobol sampler stratifies each 1-D dimension: 16 samples fall in 16
// different sixteenths.
TEST(Samplers, PaddedSobolStratifiesEachDimension) {
    auto s = createSampler("sobol", 3);
    for (int dim = 0; dim < 5; ++dim) {
        std::set<int> strata;
        for (int i = 0; i < 16; ++i) {
            s->startPixelSample(7, 2, i);
            for (int d = 0; d < dim; ++d) s->get1D();
            strata.insert(int(s->get1D() * 16));
        }
        EXPECT_EQ(strata.size(), 16u) << "dimension " << dim;
    }
}

// A render that stops early (`--time` with an unbounded --spp) takes a prefix of each pixel's
// samples: for N not a power of two or past 2^16, the first 4^k samples of every 2-D request
// are a (0,2k,2)-net, and so are the first 4^k of a later block (indices past 256 when N is
// large); N = 64 is one block. A permutation of all N indices would give the prefix random
// indices: caught here for N = 100, 1000 and 10^8.
TEST(Samplers, PaddedSobolPrefixesAreNets) {
    for (int n : {64, 100, 1000, 1 << 20, 100000000})
        for (int m : {4, 6}) {
            const int count = 1 << m;
            for (int first : {0, 1024}) {
                auto s = createSampler("sobol", 11, n);
                for (int request = 0; request < 70; ++request) {  // past the table's 64 pairs
                    std::set<std::pair<int, int>> cells[7];
                    for (int i = 0; i < count; ++i) {
                        s->startPixelSample(3, 5, first + i);
                        for (int r = 0; r < request; ++r) s->get2D();
                        const Vec2 u = s->get2D();
                        for (int a = 0; a <= m; ++a) cells[a].insert({int(u.x * (1 << a)), int(u.y * (1 << (m - a)))});
                    }
                    for (int a = 0; a <= m; ++a)
                        ASSERT_EQ(int(cells[a].size()), count)
                            << "N " << n << ", samples " << first << "+" << count << ", request " << request << ", "
                            << (1 << a) << " x " << (1 << (m - a)) << " intervals";
                }
            }
        }
}

// Blocks past the first pair the dimensions anew: the block-to-block pairing of two requests'
// strata is not the same in every block (it would be with one permutation for all blocks).
TEST(Samplers, PaddedSobolBlocksPairDimensionsAnew) {
    auto s = createSampler("sobol", 5, 100000000);
    auto pairing = [&](int block) {
        std::vector<std::pair<int, int>> p;
        for (int i = 0; i < 256; ++i) {
            s->startPixelSample(1, 1, 256 * block + i);
            const float a = s->get1D(), b = s->get1D();
            p.push_back({int(a * 16), int(b * 16)});
        }
        std::sort(p.begin(), p.end());
        return p;
    };
    const auto first = pairing(0);
    int same = 0;
    for (int block = 1; block < 9; ++block) same += pairing(block) == first;
    EXPECT_LT(same, 2);
}

// Stratified sampling: with N samples per pixel every 1-D dimension puts exactly one sample
// in each of N strata; 2-D requests fill every cell of the m x m grid (N = m^2), and in
// Latin hypercube mode every row and every column of the N x N grid exactly once.
TEST(Samplers, StratifiedAndLatinHypercubeFillEveryStratum) {
    for (bool lhs : {false, true}) {
        for (int n : {16, 12}) {
            StratifiedSampler s(9, n, lhs);
            for (int px : {0, 5}) {
                std::set<int> d0, d1x, d1y, cells;
                for (int i = 0; i < n; ++i) {
                    s.startPixelSample(px, 3, i);
                    d0.insert(int(s.get1D() * n));
                    Vec2 u = s.get2D();
                    ASSERT_GE(u.x, 0.0f);
                    ASSERT_LT(u.x, 1.0f);
                    d1x.insert(int(u.x * n));
                    d1y.insert(int(u.y * n));
                    cells.insert(int(u.x * 4) * 4 + int(u.y * 4));
                }
                EXPECT_EQ(int(d0.size()), n);
                if (lhs || n == 12) {
                    EXPECT_EQ(int(d1x.size()), n) << "columns";
                    EXPECT_EQ(int(d1y.size()), n) << "rows";
                } else {
                    EXPECT_EQ(int(cells.size()), 16) << "4x4 grid cells";
                }
            }
        }
    }
}

TEST(Permutation, IsABijection) {
    for (uint32_t n : {1u, 2u, 7u, 16u, 1000u})
        for (uint32_t seed : {0u, 123u, 0xfeedbeefu}) {
            std::set<uint32_t> seen;
            for (uint32_t i = 0; i < n; ++i) {
                uint32_t p = permuteIndex(i, n, seed);
                ASSERT_LT(p, n);
                seen.insert(p);
            }
            EXPECT_EQ(seen.size(), n);
        }
    for (int m = 0; m <= 9; ++m)
        for (uint64_t key : {0ULL, 0x9e3779b97f4a7c15ULL}) {
            std::set<uint32_t> seen;
            for (uint32_t i = 0; i < (1u << m); ++i) seen.insert(permuteNested(i, m, key));
            EXPECT_EQ(seen.size(), size_t(1) << m) << "m=" << m;
            EXPECT_LT(*seen.rbegin(), 1u << m) << "m=" << m;
        }
    for (uint32_t p : {2u, 3u, 7u, 8161u})
        for (uint64_t seed : {0ULL, 123ULL, 0xfeedbeef12345678ULL}) {
            std::set<uint32_t> seen;
            for (uint32_t i = 0; i < p; ++i) {
                uint32_t v = permutePrime(i, FastDivisor(p), seed);
                ASSERT_LT(v, p);
                seen.insert(v);
            }
            EXPECT_EQ(seen.size(), p);
        }
}

// Over random seeds every element lands in every position equally often, and (what the
// affine permutations promise) every ordered pair of distinct elements on every ordered pair
// of distinct positions: chi-square tests, 4 sigma.
TEST(Permutation, PositionsAndPairsEquallyLikely) {
    auto chi2Below4Sigma = [](const std::vector<int>& counts, double expected, double dof) {
        double chi2 = 0;
        for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
        return chi2 < dof + 4 * std::sqrt(2 * dof);
    };
    for (uint32_t n : {3u, 5u, 13u}) {
        const int trials = 20000;
        std::vector<int> kensler(n * n, 0), affine(n * n, 0), pairs(n * n, 0);
        for (int t = 0; t < trials; ++t) {
            uint64_t h = mix64(uint64_t(t) + 99);
            for (uint32_t i = 0; i < n; ++i) {
                ++kensler[i * n + permuteIndex(i, n, uint32_t(h))];
                ++affine[i * n + permutePrime(i, FastDivisor(n), h)];
            }
            ++pairs[permutePrime(0, FastDivisor(n), h) * n + permutePrime(1, FastDivisor(n), h)];
        }
        double dof = double(n - 1) * (n - 1);
        EXPECT_TRUE(chi2Below4Sigma(kensler, double(trials) / n, dof)) << "permuteIndex n=" << n;
        EXPECT_TRUE(chi2Below4Sigma(affine, double(trials) / n, dof)) << "permutePrime n=" << n;
        std::vector<int> offDiagonal;
        for (uint32_t a = 0; a < n; ++a)
            for (uint32_t b = 0; b < n; ++b)
                if (a != b) offDiagonal.push_back(pairs[a * n + b]);
                else EXPECT_EQ(pairs[a * n + b], 0);
        EXPECT_TRUE(chi2Below4Sigma(offDiagonal, double(trials) / (n * (n - 1)), double(n * (n - 1) - 1)))
            << "pairs n=" << n;
    }
}
