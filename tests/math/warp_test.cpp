#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <vector>

#include "math/equal_area.h"
#include "math/frame.h"
#include "math/warp.h"
#include "materials/stats.h"  // chi-square with pooling, Sidak levels
#include "mc/rng.h"

using namespace ps;
using namespace ps::test;

// E[f/pdf] = integral, with each sampler's own pdf: cos(theta) over the hemisphere (= pi) by
// uniform sampling, cos^2(theta) (= 2 pi / 3) by cosine sampling (f/pdf = pi cos(theta)).
TEST(Warp, HemisphereSamplersEstimateIntegrals) {
    Rng rng(2);
    int n = 100000;
    MeanSE uniform = meanAndError(n, [&] {
        Vec3 w = sampleUniformHemisphere({rng.uniform(), rng.uniform()});
        return double(w.z) / uniformHemispherePdf();
    });
    MeanSE cosine = meanAndError(n, [&] {
        Vec3 c = sampleCosineHemisphere({rng.uniform(), rng.uniform()});
        EXPECT_NEAR(length(c), 1.0f, 1e-4f);
        EXPECT_GE(c.z, 0.0f);
        return double(c.z) * c.z / cosineHemispherePdf(c.z);
    });
    std::printf("[ estimate ] uniform: %.5f +- %.5f (pi), cosine: %.5f +- %.5f (2 pi / 3)\n", uniform.mean, uniform.se, cosine.mean, cosine.se);
    EXPECT_NEAR(uniform.mean, kPi, 4 * uniform.se);
    EXPECT_NEAR(cosine.mean, 2 * kPi / 3, 4 * cosine.se);
}

TEST(Warp, ConeSamplesStayInCone) {
    Rng rng(3);
    float cosMax = std::cos(0.3f);
    for (int i = 0; i < 10000; ++i) {
        Vec3 w = sampleUniformCone({rng.uniform(), rng.uniform()}, cosMax);
        ASSERT_GE(w.z, cosMax - 1e-5f);
        ASSERT_NEAR(length(w), 1.0f, 1e-4f);
    }
}

TEST(EqualArea, RoundTripAndUnitLength) {
    Rng rng(5);
    for (int i = 0; i < 20000; ++i) {
        Vec2 p(rng.uniform(), rng.uniform());
        Vec3 w = equalAreaSquareToSphere(p);
        ASSERT_NEAR(length(w), 1.0f, 1e-4f);
        Vec2 q = equalAreaSphereToSquare(w);
        ASSERT_NEAR(p.x, q.x, 1e-3f);
        ASSERT_NEAR(p.y, q.y, 1e-3f);
    }
    // pbrt layout: +z at the centre, +x right-middle, +y bottom-middle (row index grows down).
    Vec2 c = equalAreaSphereToSquare({0, 0, 1});
    EXPECT_NEAR(c.x, 0.5f, 1e-5f);
    EXPECT_NEAR(c.y, 0.5f, 1e-5f);
    Vec2 px = equalAreaSphereToSquare({1, 0, 0});
    EXPECT_NEAR(px.x, 1.0f, 1e-5f);
    EXPECT_NEAR(px.y, 0.5f, 1e-5f);
    Vec2 py = equalAreaSphereToSquare({0, 1, 0});
    EXPECT_NEAR(py.x, 0.5f, 1e-5f);
    EXPECT_NEAR(py.y, 1.0f, 1e-5f);
}

TEST(Frame, OrthonormalAndRoundTrip) {
    Rng rng(7);
    for (int i = 0; i < 1000; ++i) {
        Vec3 n = sampleUniformSphere({rng.uniform(), rng.uniform()});
        Frame f = Frame::fromNormal(n);
        EXPECT_NEAR(dot(f.s, f.t), 0.0f, 1e-5f);
        EXPECT_NEAR(dot(f.s, f.n), 0.0f, 1e-5f);
        EXPECT_NEAR(length(f.s), 1.0f, 1e-5f);
        Vec3 v(0.3f, -0.2f, 0.9f);
        Vec3 r = f.toLocal(f.toWorld(v));
        EXPECT_NEAR(r.x, v.x, 1e-5f);
        EXPECT_NEAR(r.z, v.z, 1e-5f);
    }
}

// Every warp's samples against its density: Pearson's chi-square over a grid of the target
// domain (cells with expected count < 5 pooled), the expected counts being the warp's pdf
// integrated over each cell by sub-cell quadrature, NOT renormalised to the sample count, so
// a wrong density constant fails too. Each pdf also integrates to 1 over its domain.
// (Thesis §2.4.1: a warp is correct when its samples have the density it claims.)
namespace {

// Significance: the family of chi-square tests below rejects correct warps with probability
// 1e-3 overall (Sidak-corrected per test).
const double kWarpAlpha = sidak(1e-3, 12);

// Directions on the band z in [zMin, zMax] of the unit sphere, gridded by (z, phi): every
// cell of a row has the same solid angle, dz dphi (Archimedes).
struct ZPhiGrid {
    double zMin, zMax;
    int nZ, nPhi;
    int cells() const { return nZ * nPhi; }
    int cellOf(Vec3 w) const {
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2 * M_PI;
        int iz = std::clamp(int((w.z - zMin) / (zMax - zMin) * nZ), 0, nZ - 1);
        int ip = std::clamp(int(phi / (2 * M_PI) * nPhi), 0, nPhi - 1);
        return iz * nPhi + ip;
    }
    // Integral of a solid-angle density over each cell: midpoint rule on sub x sub points.
    std::vector<double> integrate(const std::function<double(Vec3)>& pdf, int sub) const {
        std::vector<double> out(cells());
        double dz = (zMax - zMin) / nZ, dp = 2 * M_PI / nPhi;
        for (int iz = 0; iz < nZ; ++iz)
            for (int ip = 0; ip < nPhi; ++ip) {
                double acc = 0;
                for (int i = 0; i < sub; ++i)
                    for (int j = 0; j < sub; ++j) {
                        double z = zMin + (iz + (i + 0.5) / sub) * dz, phi = (ip + (j + 0.5) / sub) * dp;
                        double r = std::sqrt(std::max(0.0, 1 - z * z));
                        acc += pdf(Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
                    }
                out[iz * nPhi + ip] = acc * dz * dp / (sub * sub);
            }
        return out;
    }
};

double sum(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
}

// Chi-square of n warped directions against n * (pdf integrated over each cell).
ChiSquareResult directionChiSquare(const char* name, const ZPhiGrid& grid, const std::function<Vec3(Vec2)>& warp,
                                   const std::function<double(Vec3)>& pdf, int n, uint64_t seed) {
    std::vector<double> expected = grid.integrate(pdf, 8), observed(grid.cells(), 0.0);
    for (double& e : expected) e *= n;
    Rng rng(seed);
    for (int i = 0; i < n; ++i) observed[grid.cellOf(warp({rng.uniform(), rng.uniform()}))] += 1;
    ChiSquareResult r = chiSquare(observed, expected);
    std::printf("[ chi2     ] %-24s chi2=%8.1f dof=%3d p=%.3g (expected total %.5f n)\n", name, r.chi2, r.dof, r.pValue,
                sum(expected) / n);
    return r;
}

// Integral of a solid-angle density over the band, by the same quadrature on a fine grid.
double integrateBand(double zMin, double zMax, const std::function<double(Vec3)>& pdf) {
    return sum(ZPhiGrid{zMin, zMax, 200, 200}.integrate(pdf, 2));
}

}  // namespace

TEST(Warp, CosineHemisphereFollowsItsPdf) {
    auto pdf = [](Vec3 w) { return double(cosineHemispherePdf(w.z)); };
    EXPECT_NEAR(integrateBand(-1, 1, pdf), 1.0, 1e-4);  // zero below the horizon
    // The grid covers the whole sphere so samples below the horizon would fail.
    ChiSquareResult r = directionChiSquare("CosineHemisphere", {-1, 1, 40, 32}, sampleCosineHemisphere, pdf, 200000, 21);
    EXPECT_GT(r.pValue, kWarpAlpha) << r.chi2;
}

TEST(Warp, UniformSphereFollowsItsPdf) {
    auto pdf = [](Vec3) { return double(uniformSpherePdf()); };
    EXPECT_NEAR(integrateBand(-1, 1, pdf), 1.0, 1e-5);
    ChiSquareResult r = directionChiSquare("UniformSphere", {-1, 1, 20, 32}, sampleUniformSphere, pdf, 200000, 22);
    EXPECT_GT(r.pValue, kWarpAlpha) << r.chi2;
}

TEST(Warp, UniformHemisphereFollowsItsPdf) {
    auto pdf = [](Vec3 w) { return w.z >= 0 ? double(uniformHemispherePdf()) : 0.0; };
    EXPECT_NEAR(integrateBand(-1, 1, pdf), 1.0, 1e-5);
    ChiSquareResult r = directionChiSquare("UniformHemisphere", {-1, 1, 40, 32}, sampleUniformHemisphere, pdf, 200000, 23);
    EXPECT_GT(r.pValue, kWarpAlpha) << r.chi2;
}

// A narrow cone (gridded over the cone only, where the resolution is needed) and a cone
// wider than a hemisphere (over the whole sphere, so samples outside it fail).
TEST(Warp, UniformConeFollowsItsPdf) {
    for (float cosMax : {std::cos(0.3f), -0.5f}) {
        auto pdf = [&](Vec3 w) { return w.z >= cosMax ? double(uniformConePdf(cosMax)) : 0.0; };
        EXPECT_NEAR(integrateBand(cosMax, 1, pdf), 1.0, 1e-4) << cosMax;
        ZPhiGrid grid = cosMax > 0 ? ZPhiGrid{cosMax, 1, 20, 32} : ZPhiGrid{-1, 1, 40, 32};
        auto warp = [&](Vec2 u) { return sampleUniformCone(u, cosMax); };
        ChiSquareResult r = directionChiSquare(cosMax > 0 ? "UniformConeNarrow" : "UniformConeWide", grid, warp, pdf, 200000, 24);
        EXPECT_GT(r.pValue, kWarpAlpha) << cosMax << " chi2=" << r.chi2;
    }
}

// Equal area (square -> sphere): uniform points on the square give density 1/(4 pi).
TEST(EqualArea, SquareToSphereIsUniform) {
    auto pdf = [](Vec3) { return 1 / (4 * M_PI); };
    ChiSquareResult r = directionChiSquare("EqualAreaSquareToSphere", {-1, 1, 24, 36}, equalAreaSquareToSphere, pdf, 300000, 25);
    EXPECT_GT(r.pValue, kWarpAlpha) << r.chi2;
}

// And the inverse (sphere -> square) takes uniform directions to uniform points: every texel
// of an equal-area environment map subtends 4 pi / N.
TEST(EqualArea, SphereToSquareIsUniform) {
    const int nCells = 24, n = 300000;
    std::vector<double> observed(nCells * nCells, 0.0), expected(nCells * nCells, double(n) / (nCells * nCells));
    Rng rng(26);
    for (int i = 0; i < n; ++i) {
        Vec2 p = equalAreaSphereToSquare(sampleUniformSphere({rng.uniform(), rng.uniform()}));
        int x = std::min(nCells - 1, int(p.x * nCells)), y = std::min(nCells - 1, int(p.y * nCells));
        observed[y * nCells + x] += 1;
    }
    ChiSquareResult r = chiSquare(observed, expected);
    std::printf("[ chi2     ] %-24s chi2=%8.1f dof=%3d p=%.3g\n", "EqualAreaSphereToSquare", r.chi2, r.dof, r.pValue);
    EXPECT_GT(r.pValue, kWarpAlpha) << r.chi2;
}

// Concentric disk: density 1/pi on the unit disk, on a polar grid of equal-area cells
// (equal steps in r^2 and in angle), turned by 0.1 rad so no cell edge follows the map's
// own seams along the diagonals.
TEST(Warp, ConcentricDiskIsUniform) {
    const int nR = 12, nA = 24, n = 200000;
    std::vector<double> observed(nR * nA, 0.0), expected(nR * nA, double(n) / (nR * nA));
    Rng rng(27);
    for (int i = 0; i < n; ++i) {
        Vec2 d = sampleConcentricDisk({rng.uniform(), rng.uniform()});
        double r2 = double(d.x) * d.x + double(d.y) * d.y;
        ASSERT_LE(r2, 1 + 1e-5);
        double a = std::atan2(double(d.y), double(d.x)) - 0.1;
        a -= 2 * M_PI * std::floor(a / (2 * M_PI));
        int ir = std::min(nR - 1, int(r2 * nR)), ia = std::min(nA - 1, int(a / (2 * M_PI) * nA));
        observed[ir * nA + ia] += 1;
    }
    ChiSquareResult r = chiSquare(observed, expected);
    std::printf("[ chi2     ] %-24s chi2=%8.1f dof=%3d p=%.3g\n", "ConcentricDisk", r.chi2, r.dof, r.pValue);
    EXPECT_GT(r.pValue, kWarpAlpha) << r.chi2;
}

// Triangle: density 2 on {b0, b1 >= 0, b0 + b1 <= 1}. On an n x n grid of the unit square
// the diagonal cuts cells exactly in half, so the expected counts are exact.
TEST(Warp, TriangleIsUniform) {
    const int nCells = 20, n = 200000;
    std::vector<double> observed(nCells * nCells, 0.0), expected(nCells * nCells, 0.0);
    const double cellMass = 2.0 / (nCells * nCells);  // density 2 times the cell's area
    for (int i = 0; i < nCells; ++i)
        for (int j = 0; j < nCells; ++j) expected[i * nCells + j] = n * (i + j < nCells - 1 ? cellMass : i + j == nCells - 1 ? cellMass / 2 : 0);
    Rng rng(28);
    for (int k = 0; k < n; ++k) {
        Vec2 b = sampleUniformTriangle({rng.uniform(), rng.uniform()});
        ASSERT_GE(b.x, 0.0f);
        ASSERT_GE(b.y, 0.0f);
        ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
        int i = std::min(nCells - 1, int(b.x * nCells)), j = std::min(nCells - 1, int(b.y * nCells));
        observed[i * nCells + j] += 1;
    }
    ChiSquareResult r = chiSquare(observed, expected);
    std::printf("[ chi2     ] %-24s chi2=%8.1f dof=%3d p=%.3g\n", "Triangle", r.chi2, r.dof, r.pValue);
    EXPECT_GT(r.pValue, kWarpAlpha) << r.chi2;
}
