// Perlin noise and its octave sums (materials/noise.h): values of pbrt-v4's Noise at chosen
// points, the lattice zeros and period that follow from the definition, the range, fbm and
// turbulence as their sums of octaves, and the polka-dot pattern of the dots texture.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "materials/noise.h"
#include "materials/procedural_textures.h"

using namespace ps;

namespace {

// pbrt-v4's Noise(x, y, z) at these points, computed with pbrt-v4's own code (commit
// 5f7a606, util/noise.cpp, single precision). Our evaluation order differs (the fade
// polynomial in Horner form), so agreement is to float rounding, not bit for bit.
struct NoiseValue {
    float x, y, z;
    double value;
};
const NoiseValue kPbrtNoise[] = {
    {0.3f, 0.7f, 0.1f, -0.0971813723},         {1.25f, -3.5f, 2.75f, 0.235721111},
    {10.1f, 20.2f, -30.3f, 0.268966198},       {100.37f, 5.11f, 0.5f, 0.21896182},
    {3.9f, 1.1f, 7.7f, -0.328137904},          {-7.3f, -0.2f, -5.6f, -0.267357171},
    {1000.6f, -2000.3f, 123.4f, -0.0552258715},
};

}  // namespace

TEST(Noise, MatchesPbrtV4AtChosenPoints) {
    for (const NoiseValue& v : kPbrtNoise) {
        float n = perlinNoise(v.x, v.y, v.z);
        std::printf("  noise(%g, %g, %g) = %.9f, pbrt-v4 %.9f\n", v.x, v.y, v.z, n, v.value);
        EXPECT_NEAR(n, v.value, 2e-6) << v.x << "," << v.y << "," << v.z;
    }
    // The 2-D form is the 3-D one at z = 0.5.
    EXPECT_EQ(perlinNoise(100.37f, 5.11f), perlinNoise(100.37f, 5.11f, 0.5f));
}

// Every lattice point is a zero: the offsets to its own corner are 0 and the other corners
// have weight 0. The lattice repeats every 256 (the permutation table's size).
TEST(Noise, ZeroOnTheLatticeAndPeriodic) {
    for (int x = -3; x <= 3; ++x)
        for (int y = -3; y <= 3; ++y)
            for (int z : {-300, -1, 0, 2, 255, 1000000}) EXPECT_EQ(perlinNoise(float(x), float(y), float(z)), 0.0f);
    // Dyadic coordinates: shifting by 256 is exact in float, and so is the result.
    for (float x : {0.125f, 0.5f, 3.375f})
        for (float y : {-0.25f, 1.75f}) {
            float n = perlinNoise(x, y, 0.625f);
            EXPECT_EQ(perlinNoise(x + 256, y, 0.625f), n);
            EXPECT_EQ(perlinNoise(x, y - 512, 0.625f), n);
            EXPECT_EQ(perlinNoise(x, y, 0.625f + 256), n);
        }
    EXPECT_EQ(perlinNoise(INFINITY, 0, 0), 0.0f);
    EXPECT_EQ(perlinNoise(0.5f, NAN, 0), 0.0f);
}

// Gradient noise of this kind stays within about [-1, 1]; it is far from constant and has
// mean near zero over many cells.
TEST(Noise, RangeAndMean) {
    double maxAbs = 0, sum = 0;
    int n = 0;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 64; ++j)
            for (int k = 0; k < 16; ++k) {
                float v = perlinNoise(i * 0.3719f, j * 0.2913f - 7, k * 0.6131f + 0.1f);
                maxAbs = std::max(maxAbs, double(std::fabs(v)));
                sum += v;
                ++n;
            }
    std::printf("  max |noise| %.4f, mean %.4f over %d points\n", maxAbs, sum / n, n);
    EXPECT_LT(maxAbs, 1.1);
    EXPECT_GT(maxAbs, 0.6);
    EXPECT_LT(std::fabs(sum / n), 0.02);
}

// fbm and turbulence are the sums of their octaves, the frequency growing by 1.99 each time;
// turbulence adds 0.2 omega^octaves for the octave beyond (pbrt-v4 with no filter footprint).
TEST(Noise, OctaveSums) {
    const Vec3 p(1.3f, -2.7f, 0.45f);
    const float omega = 0.6f;
    EXPECT_EQ(fbm(p, omega, 0), 0.0f);
    EXPECT_EQ(fbm(p, omega, 1), perlinNoise(p));
    float n0 = perlinNoise(p), n1 = perlinNoise(p * 1.99f), n2 = perlinNoise(p * (1.99f * 1.99f));
    EXPECT_NEAR(fbm(p, omega, 3), n0 + omega * n1 + omega * omega * n2, 1e-6);
    EXPECT_NEAR(turbulence(p, omega, 0), 0.2f, 1e-7);
    EXPECT_NEAR(turbulence(p, omega, 1), std::fabs(n0) + 0.2f * omega, 1e-6);
    EXPECT_NEAR(turbulence(p, omega, 3), std::fabs(n0) + omega * std::fabs(n1) + omega * omega * std::fabs(n2) + 0.2f * omega * omega * omega,
                1e-6);
    std::printf("  fbm %.6f, turbulence %.6f (3 octaves, omega 0.6)\n", fbm(p, omega, 3), turbulence(p, omega, 3));
}

// The dots pattern on an 80 x 80 grid over [-3, 7)^2 matches pbrt-v4's InsidePolkaDot point
// for point: the count and an FNV-1a fingerprint of the inside/outside bits, both computed
// with pbrt-v4's own code on the same float coordinates.
TEST(Noise, PolkaDotsMatchPbrtV4) {
    uint64_t h = 1469598103934665603ull;
    int inside = 0;
    for (int j = 0; j < 80; ++j)
        for (int i = 0; i < 80; ++i) {
            bool in = insidePolkaDot(Vec2(-3 + i / 8.0f + 1 / 16.0f, -3 + j / 8.0f + 1 / 16.0f));
            inside += in;
            h = (h ^ (in ? 1ull : 0ull)) * 1099511628211ull;
        }
    std::printf("  %d of 6400 grid points inside a dot, fingerprint %llu\n", inside, (unsigned long long)h);
    EXPECT_EQ(inside, 1160);
    EXPECT_EQ(h, 1635880967369200577ull);
    EXPECT_FALSE(insidePolkaDot(Vec2(1e30f, 0.5f)));
    EXPECT_FALSE(insidePolkaDot(Vec2(NAN, 0.5f)));
}
