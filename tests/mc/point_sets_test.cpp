// Point sets: the structural property each one promises, and Sobol's published points.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "mc/point_sets.h"
#include "mc/sobol.h"
#include "mc/sobol_matrices.h"

using namespace ps;

namespace {

void expectInUnitCube(const PointSet& p) {
    for (double x : p.data) {
        ASSERT_GE(x, 0.0);
        ASSERT_LT(x, 1.0);
    }
}

}  // namespace

TEST(PointSets, StratifiedHasExactlyOnePointPerCell) {
    Rng rng(1);
    for (int dims = 1; dims <= 5; ++dims) {
        const int n = 1000;
        PointSet p = generatePoints(PointSetKind::Stratified, n, dims, rng);
        int k = int(std::lround(std::pow(p.n, 1.0 / dims)));
        int size = 1;
        for (int d = 0; d < dims; ++d) size *= k;
        ASSERT_EQ(p.n, size) << "dims " << dims;
        ASSERT_LE(p.n, n);
        ASSERT_GT(std::pow(k + 1, dims), n) << "the largest grid that fits";
        expectInUnitCube(p);
        std::set<int64_t> cells;
        for (int i = 0; i < p.n; ++i) {
            int64_t cell = 0;
            for (int d = 0; d < dims; ++d) cell = cell * k + int64_t(p.point(i)[d] * k);
            cells.insert(cell);
        }
        EXPECT_EQ(int(cells.size()), p.n) << "dims " << dims;
    }
}

TEST(PointSets, LatinHypercubeHasOnePointPerRowInEveryDimension) {
    Rng rng(2);
    const int n = 97, dims = 6;
    PointSet p = generatePoints(PointSetKind::LatinHypercube, n, dims, rng);
    ASSERT_EQ(p.n, n);
    expectInUnitCube(p);
    for (int d = 0; d < dims; ++d) {
        std::set<int> rows;
        for (int i = 0; i < n; ++i) rows.insert(int(p.point(i)[d] * n));
        EXPECT_EQ(int(rows.size()), n) << "dimension " << d;
    }
}

TEST(SobolMatrices, FirstPointsMatchPublishedValues) {
    // Joe and Kuo's direction numbers, points in natural order (index i, not Gray code).
    const double expected[5][8] = {
        {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875},
        {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875},
        {0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125},
        {0, 0.5, 0.75, 0.25, 0.125, 0.625, 0.875, 0.375},
        {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875},
    };
    for (int d = 0; d < 5; ++d)
        for (uint32_t i = 0; i < 8; ++i) EXPECT_EQ(sobolSample(i, d) * 0x1p-32, expected[d][i]) << d << "," << i;
    // The first two dimensions agree with the renderer's sobol.h.
    for (uint32_t i = 0; i < 4096; ++i) {
        ASSERT_EQ(sobolSample(i, 0), sobolDim0(i));
        ASSERT_EQ(sobolSample(i, 1), sobolDim1(i));
    }
}

TEST(SobolMatrices, EveryDimensionIsA01SequenceAndPairsAreNets) {
    // Each coordinate alone: the first 2^m points hit each of the 2^m intervals once.
    const int m = 10, n = 1 << m;
    for (int d = 0; d < kSobolMaxDims; ++d) {
        std::set<uint32_t> cells;
        for (uint32_t i = 0; i < n; ++i) cells.insert(sobolSample(i, d) >> (32 - m));
        EXPECT_EQ(int(cells.size()), n) << "dimension " << d;
    }
    // Dimensions 0 and 1 form a (0,m,2)-net: every 2^a x 2^(m-a) box holds one point.
    for (int a = 0; a <= m; ++a) {
        std::set<uint64_t> boxes;
        for (uint32_t i = 0; i < n; ++i)
            boxes.insert((uint64_t(a ? sobolSample(i, 0) >> (32 - a) : 0) << 32) |
                         (m - a ? sobolSample(i, 1) >> (32 - (m - a)) : 0));
        EXPECT_EQ(int(boxes.size()), n) << "a = " << a;
    }
}

TEST(PointSets, ScrambledSobolKeepsStratificationAndVariesWithTheSeed) {
    Rng rng(3);
    const int m = 8, n = 1 << m, dims = 10;
    PointSet p = generatePoints(PointSetKind::Sobol, n, dims, rng);
    expectInUnitCube(p);
    for (int d = 0; d < dims; ++d) {
        std::set<int> cells;
        for (int i = 0; i < n; ++i) cells.insert(int(p.point(i)[d] * n));
        EXPECT_EQ(int(cells.size()), n) << "dimension " << d;
    }
    PointSet q = generatePoints(PointSetKind::Sobol, n, dims, rng);
    EXPECT_NE(p.data, q.data);
    EXPECT_THROW(generatePoints(PointSetKind::Sobol, 4, 11, rng), std::invalid_argument);
}

TEST(PointSets, NamesRoundTrip) {
    for (PointSetKind k : {PointSetKind::Independent, PointSetKind::Stratified, PointSetKind::LatinHypercube,
                           PointSetKind::Sobol})
        EXPECT_EQ(pointSetKindFromName(pointSetName(k)), k);
    EXPECT_FALSE(pointSetKindFromName("halton"));
}
