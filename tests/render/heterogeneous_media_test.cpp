// Heterogeneous media (issue 36): pbrt-v4's "cloud" density against pbrt-v4's own numbers,
// the majorant grid's bound on the density in every cell and along rays (what delta and
// ratio tracking rely on), and ratio-tracked transmittance through the cloud against a
// quadrature of exp(-integral of sigma_t).
#include <gtest/gtest.h>

#include <cmath>

#include "media/cloud_medium.h"
#include "media/grid_medium.h"
#include "materials/noise.h"
#include "media_test_helpers.h"
#include "scene/color_space.h"

using namespace ps;
using namespace ps::test;

namespace {

MediumSpectrum constantSpectrum(float v) { return MediumSpectrum(Spectrum(v), SpectrumSource::constant(v), 1); }

// Printed by pbrt-v4 (commit 5f7a606) itself: its util/noise.cpp compiled with a program that
// evaluates CloudMedium::Density's formula (media.h) with pbrt's Noise and DNoise, at the
// point p in the medium's space for (density, wispiness, frequency) = (1, 1, 5), (2.5, 0, 3)
// and (0.7, 2, 7); and Noise(3.1 p).
struct PbrtCloudValue {
    Vec3 p;
    float noise, d1, d2, d3;
};
constexpr PbrtCloudValue kPbrtCloud[] = {
    {{0.300000012f, 0.600000024f, 0.400000006f}, -0.0914327204f, 0.0f, 0.0f, 0.0f},
    {{0.709999979f, 0.550000012f, 0.200000003f}, -0.0391035788f, 0.242739528f, 0.0f, 0.394026667f},
    {{0.119999997f, 0.829999983f, 0.899999976f}, 0.436278701f, 0.0940293297f, 0.658179462f, 0.10689237f},
    {{0.5f, 0.5f, 0.5f}, -0.603411078f, 0.0880670547f, 0.0f, 0.0f},
    {{0.25f, 0.300000012f, 0.75f}, -0.347455472f, 0.654222488f, 0.399999976f, 0.399999976f},
    {{0.899999976f, 0.949999988f, 0.0500000007f}, 0.0358826891f, 0.0f, 0.0668793693f, 0.0f},
    {{1.70000005f, 1.20000005f, -0.400000006f}, -0.0171993058f, 0.0868756771f, 0.0f, 0.100381069f},
    {{0.330000013f, 0.519999981f, 0.610000014f}, -0.0474204868f, 0.224216715f, 0.537064254f, 0.0f},
};

CloudMedium cloud(CloudMedium::Shape shape, Vec3 p0 = {0, 0, 0}, Vec3 p1 = {1, 1, 1}) {
    return CloudMedium(MediumBox{Transform(), p0, p1}, constantSpectrum(1), constantSpectrum(0), 0, shape);
}

}  // namespace

TEST(CloudMedium, NoiseAndDensityAreThoseOfPbrtV4) {
    for (const PbrtCloudValue& v : kPbrtCloud) {
        // Float rounding (operation order, fused multiply-adds) is all that may differ.
        EXPECT_NEAR(perlinNoise(v.p * 3.1f), v.noise, 2e-6f) << v.p.x << " " << v.p.y << " " << v.p.z;
        EXPECT_NEAR(cloud({1, 1, 5}).density(v.p), v.d1, 1e-4f) << v.p.x << " " << v.p.y << " " << v.p.z;
        EXPECT_NEAR(cloud({2.5f, 0, 3}).density(v.p), v.d2, 1e-4f) << v.p.x << " " << v.p.y << " " << v.p.z;
        EXPECT_NEAR(cloud({0.7f, 2, 7}).density(v.p), v.d3, 1e-4f) << v.p.x << " " << v.p.y << " " << v.p.z;
    }
    // Perlin noise vanishes on the integer lattice.
    EXPECT_EQ(perlinNoise(Vec3(3, -7, 12)), 0.0f);
}

// The cloud's cells bound its density: a box from below y = 0 to above y = 1 and a thin
// cloud, so that the bound is below 1 in many cells and the solid base below y = 1/2 must be
// in it (without it the test fails: 0.6 at y = 0.2 against a noise bound of 0.14).
TEST(CloudMedium, MajorantGridBoundsTheDensityInEveryCell) {
    const CloudMedium c = cloud({0.03f, 1, 5}, {-0.5f, -0.2f, 0}, {1, 1.8f, 0.6f});
    int below1 = 0;
    for (float m : c.majorantGrid().cells) below1 += m < 1;
    EXPECT_GT(below1, 0) << "no cell's bound is below 1: the test would not catch a wrong bound";
    const Vec3 e = c.box().p1 - c.box().p0;
    const int bad = countCellViolations(c.majorantGrid(), 24, [&](Vec3 p) { return Spectrum(c.density(p)); },
                                        [&](Vec3 u) { return c.box().p0 + Vec3(u.x * e.x, u.y * e.y, u.z * e.z); });
    EXPECT_EQ(bad, 0);
    std::printf("  %d of %zu cells below 1\n", below1, c.majorantGrid().cells.size());
}

// A peaky uniformgrid (most voxels 0, a few large) in a box placed by p0 and p1: each 16^3
// cell's majorant is at least the density anywhere in it, and along random rays each DDA
// segment's majorant bounds sigma_t inside that segment, and the segments tile the clipped ray.
TEST(GridMedium, MajorantGridBoundsTheDensityInCellsAndAlongRays) {
    VoxelGrid<float> g;
    g.nx = 23, g.ny = 7, g.nz = 40;
    Rng rng(3);
    for (int i = 0; i < g.nx * g.ny * g.nz; ++i) g.values.push_back(rng.uniform() < 0.05f ? 20 * rng.uniform() : 0.0f);
    VoxelGrid<float> le;
    le.values = {1};
    const MediumBox box{Transform(), {-1, 0, 2}, {1, 3, 4}};
    const GridMedium m(box, g, constantSpectrum(1), constantSpectrum(0.5f), MediumSpectrum(), le, 0);
    auto sigmaT = [&](Vec3 p) {
        const MediumProperties mp = m.at(p, nullptr);
        return mp.sigmaA + mp.sigmaS;
    };
    const Vec3 e = box.p1 - box.p0;
    auto toWorld = [&](Vec3 u) { return box.p0 + Vec3(u.x * e.x, u.y * e.y, u.z * e.z); };
    EXPECT_EQ(countCellViolations(m.majorantGrid(false), 16, [&](Vec3 p) { return sigmaT(p) / 1.5f; }, toWorld), 0);
    int bad = 0, segments = 0;
    for (int r = 0; r < 2000; ++r) {
        const Vec3 o = toWorld(Vec3(rng.uniform() * 1.4f - 0.2f, rng.uniform() * 1.4f - 0.2f, rng.uniform() * 1.4f - 0.2f));
        const float phi = 2 * 3.14159265f * rng.uniform(), cz = 2 * rng.uniform() - 1, sz = std::sqrt(1 - cz * cz);
        const Vec3 d(sz * std::cos(phi), sz * std::sin(phi), cz);
        MajorantIterator it = m.majorants(o, d, 10, nullptr);
        MajorantSegment seg;
        float last = -1;
        while (it.next(&seg)) {
            ++segments;
            if (last >= 0 && std::abs(seg.t0 - last) > 1e-5f) ++bad;  // gaps between segments
            last = seg.t1;
            for (int i = 0; i < 8; ++i) {
                const float t = seg.t0 + (seg.t1 - seg.t0) * (i + 0.5f) / 8;
                const Spectrum s = sigmaT(o + d * t);
                if (s.r > seg.sigmaMaj.r * (1 + 1e-5f) + 1e-6f && bad++ < 5)
                    ADD_FAILURE() << "ray " << r << " t " << t << ": sigma_t " << s.r << " > majorant " << seg.sigmaMaj.r;
            }
        }
    }
    EXPECT_EQ(bad, 0);
    EXPECT_GT(segments, 10000) << "the rays should cross many cells";
}

// An rgbgrid's cells bound sigma_a + sigma_s per channel in RGB mode and the lifted spectra's
// values at sampled wavelengths in spectral mode.
TEST(GridMedium, RgbGridMajorantsBoundBothColourModes) {
    VoxelGrid<Spectrum> a, s;
    a.nx = s.nx = 5, a.ny = s.ny = 9, a.nz = s.nz = 3;
    Rng rng(5);
    for (int i = 0; i < 5 * 9 * 3; ++i) {
        a.values.push_back(Spectrum(rng.uniform(), 3 * rng.uniform(), 0.2f * rng.uniform()));
        s.values.push_back(rng.uniform() < 0.2f ? Spectrum(5 * rng.uniform(), rng.uniform(), 2 * rng.uniform()) : Spectrum(0.0f));
    }
    const GridMedium m(MediumBox{Transform(), {0, 0, 0}, {1, 1, 1}}, a, s, &srgbColorSpace(), 0);
    auto rgb = [&](Vec3 p) {
        const MediumProperties mp = m.at(p, nullptr);
        return mp.sigmaA + mp.sigmaS;
    };
    EXPECT_EQ(countCellViolations(m.majorantGrid(false), 8, rgb, [](Vec3 u) { return u; }), 0);
    Rng wl(9);
    auto spectral = [&](Vec3 p) {
        const SampledWavelengths lambda = SampledWavelengths::sampleVisible(wl.uniform());
        const MediumProperties mp = m.at(p, &lambda);
        return mp.sigmaA + mp.sigmaS;
    };
    EXPECT_EQ(countCellViolations(m.majorantGrid(true), 8, spectral, [](Vec3 u) { return u; }), 0);
}

// Ratio tracking through the cloud (walking its majorant grid) against exp(-tau), tau by a
// midpoint rule of sigma_t along the segment with 20000 steps (its error is far below the
// estimate's sigma): chromatic sigma_s, rays across, diagonally through and from inside the box.
TEST(CloudMedium, RatioTrackedTransmittanceIsExpMinusOpticalDepth) {
    auto scene = sceneInMedium(R"("string type" "cloud" "rgb sigma_a" [ 1.5 1.5 1.5 ] "rgb sigma_s" [ 3 4.5 7.5 ]
                                  "float density" [ 1.2 ] "point3 p0" [ -0.5 0 0 ] "point3 p1" [ 1 1.3 1 ])");
    const Medium& medium = *scene->cameraMedium();
    struct Segment {
        Vec3 a, b;
    };
    for (const Segment& s : {Segment{{-1, 0.7f, 0.5f}, {1.5f, 0.7f, 0.5f}}, Segment{{-0.4f, 0.45f, 0.1f}, {0.9f, 1.2f, 0.9f}},
                             Segment{{0.2f, 0.55f, 0.5f}, {0.3f, 0.6f, 3}}}) {
        // Only inside the box: the density formula goes on outside it, tracking does not.
        auto inBox = [](Vec3 p) { return p.x >= -0.5f && p.x <= 1 && p.y >= 0 && p.y <= 1.3f && p.z >= 0 && p.z <= 1; };
        const std::array<double, 3> tau = opticalDepth(medium, s.a, s.b, 20000, inBox);
        const std::array<double, 3> exact{std::exp(-tau[0]), std::exp(-tau[1]), std::exp(-tau[2])};
        std::printf("  tau %.4f %.4f %.4f\n", tau[0], tau[1], tau[2]);
        expectTransmittance(ratioTracked(*scene, s.a, s.b, 40000), exact, "cloud");
    }
}
