// The 2D piecewise-linear warp (mc/piecewise_linear_2d.h): its samples follow its density
// (chi-square on a histogram), invert() undoes sample(), the density integrates to 1, the
// parameter slices blend linearly, and bad tables are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "materials/stats.h"
#include "mc/piecewise_linear_2d.h"
#include "mc/rng.h"

using namespace ps;
using Mode = PiecewiseLinear2D::Mode;

namespace {

// A lopsided density on a 5x4 grid (with a zero corner), and a second slice unlike it.
std::vector<float> twoSlices() {
    std::vector<float> d;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) d.push_back(x == 0 && y == 0 ? 0.0f : 0.2f + float(x * x) + 2.0f * float(y % 2));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) d.push_back(1.0f + 3.0f * float(y) + float((x + y) % 3));
    return d;
}

// Integral of the density over a cell of a k x k histogram, by the midpoint rule on sub^2 points.
double cellIntegral(const PiecewiseLinear2D& w, const float* param, int k, int cx, int cy, int sub) {
    double acc = 0;
    for (int i = 0; i < sub; ++i)
        for (int j = 0; j < sub; ++j)
            acc += w.evaluate(Vec2((cx + (i + 0.5f) / sub) / k, (cy + (j + 0.5f) / sub) / k), param);
    return acc / (double(sub) * sub * k * k);
}

}  // namespace

TEST(PiecewiseLinear2D, SamplesFollowTheDensity) {
    std::vector<float> d = twoSlices();
    PiecewiseLinear2D w(d.data(), 5, 4, {{0.0f, 1.0f}}, Mode::Warp);
    const float param[1] = {0.3f};  // between the slices
    const int k = 16, n = 200000;
    std::vector<double> observed(k * k, 0), expected(k * k);
    Rng rng(11);
    for (int i = 0; i < n; ++i) {
        auto s = w.sample(Vec2(rng.uniform(), rng.uniform()), param);
        int cx = std::min(k - 1, int(s.p.x * k)), cy = std::min(k - 1, int(s.p.y * k));
        observed[cy * k + cx] += 1;
    }
    for (int cy = 0; cy < k; ++cy)
        for (int cx = 0; cx < k; ++cx) expected[cy * k + cx] = n * cellIntegral(w, param, k, cx, cy, 8);
    auto r = test::chiSquare(observed, expected);
    std::printf("  chi2 %.1f, dof %d, p %.3g (%d samples, %dx%d cells)\n", r.chi2, r.dof, r.pValue, n, k, k);
    EXPECT_GT(r.pValue, 1e-4);
}

TEST(PiecewiseLinear2D, InvertUndoesSampleAndPdfsAgree) {
    std::vector<float> d = twoSlices();
    PiecewiseLinear2D w(d.data(), 5, 4, {{0.0f, 1.0f}}, Mode::Warp);
    Rng rng(12);
    double worstU = 0, worstPdf = 0;
    for (int i = 0; i < 20000; ++i) {
        const float param[1] = {rng.uniform() * 1.4f - 0.2f};  // also beyond the ends (clamped)
        Vec2 u(rng.uniform(), rng.uniform());
        auto s = w.sample(u, param);
        auto inv = w.invert(s.p, param);
        worstU = std::max({worstU, double(std::fabs(inv.p.x - u.x)), double(std::fabs(inv.p.y - u.y))});
        worstPdf = std::max(worstPdf, std::fabs(double(inv.pdf) / s.pdf - 1));
        worstPdf = std::max(worstPdf, std::fabs(double(w.evaluate(s.p, param)) / s.pdf - 1));
    }
    std::printf("  largest |invert(sample(u)) - u| %.3g, largest relative pdf difference %.3g\n", worstU, worstPdf);
    EXPECT_LT(worstU, 2e-4);
    EXPECT_LT(worstPdf, 1e-4);
}

TEST(PiecewiseLinear2D, DensityIntegratesToOneAndSlicesBlend) {
    std::vector<float> d = twoSlices();
    PiecewiseLinear2D w(d.data(), 5, 4, {{0.0f, 1.0f}}, Mode::Warp);
    PiecewiseLinear2D first(d.data(), 5, 4, {}, Mode::Warp), second(d.data() + 20, 5, 4, {}, Mode::Warp);
    for (float t : {0.0f, 0.25f, 1.0f}) {
        const float param[1] = {t};
        double total = 0;
        for (int cy = 0; cy < 4; ++cy)
            for (int cx = 0; cx < 4; ++cx) total += cellIntegral(w, param, 4, cx, cy, 64);
        std::printf("  param %.2f: integral %.7f\n", t, total);
        EXPECT_NEAR(total, 1.0, 1e-5);
        // Each slice is normalised on its own; between slices the densities blend linearly.
        Vec2 p(0.37f, 0.81f);
        EXPECT_NEAR(w.evaluate(p, param), (1 - t) * first.evaluate(p) + t * second.evaluate(p), 1e-5);
    }
}

TEST(PiecewiseLinear2D, InterpolantKeepsValuesAndBlendsParameters) {
    std::vector<float> d = twoSlices();
    PiecewiseLinear2D v(d.data(), 5, 4, {{10.0f, 20.0f}}, Mode::Interpolant);
    const float p0[1] = {10}, pMid[1] = {12.5f}, pBeyond[1] = {99};
    EXPECT_FLOAT_EQ(v.evaluate(Vec2(0.25f, 1.0f / 3), p0), d[1 * 5 + 1]);        // a grid point
    EXPECT_FLOAT_EQ(v.evaluate(Vec2(1, 1), pBeyond), d[20 + 19]);                // clamped to the last slice
    float bilinear = 0.25f * (d[0] + d[1] + d[5] + d[6]);                         // a patch centre
    float bilinear2 = 0.25f * (d[20] + d[21] + d[25] + d[26]);
    EXPECT_NEAR(v.evaluate(Vec2(0.125f, 1.0f / 6), pMid), 0.75f * bilinear + 0.25f * bilinear2, 1e-5);
}

TEST(PiecewiseLinear2D, RefusesBadTables) {
    std::vector<float> d(8, 1.0f);
    EXPECT_THROW(PiecewiseLinear2D(d.data(), 1, 8, {}, Mode::Warp), std::invalid_argument);      // below 2x2
    std::vector<float> zero(4, 0.0f), negative{1, -1, 1, 1}, nan{1, NAN, 1, 1};
    EXPECT_THROW(PiecewiseLinear2D(zero.data(), 2, 2, {}, Mode::Warp), std::invalid_argument);
    EXPECT_THROW(PiecewiseLinear2D(negative.data(), 2, 2, {}, Mode::Warp), std::invalid_argument);
    EXPECT_THROW(PiecewiseLinear2D(nan.data(), 2, 2, {}, Mode::Interpolant), std::invalid_argument);
    EXPECT_THROW(PiecewiseLinear2D(d.data(), 2, 2, {{1.0f, 0.0f}}, Mode::Warp), std::invalid_argument);  // unsorted
    EXPECT_NO_THROW(PiecewiseLinear2D(negative.data(), 2, 2, {}, Mode::Interpolant));
}
