// The NanoVDB reader and the "nanovdb" medium (issue 36): the values of tests/data/media/
// tiny.nvdb against those tests/tools/make_nvdb.cpp wrote (nvdb_test_grid.h), uncompressed and
// ZIP, trilinear sampling, the 64^3 majorant grid's bound, ratio-tracked transmittance through
// the medium, and bad files as located errors naming the file, never crashes.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "media/nanovdb_file.h"
#include "media/nanovdb_medium.h"
#include "media_test_helpers.h"
#include "tools/nvdb_test_grid.h"

using namespace ps;
using namespace ps::test;

namespace {

const std::string kDir = PATHSPACE_SOURCE_DIR "/tests/data/media/";

std::vector<uint8_t> fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The error message of parsing `bytes` for "density", or "" if it parsed.
std::string parseError(const std::vector<uint8_t>& bytes) {
    try {
        parseNanoVDBGrid(bytes.data(), bytes.size(), "density", "bad.nvdb");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

float trilinear(Vec3 p) {
    const int i = int(std::floor(p.x)), j = int(std::floor(p.y)), k = int(std::floor(p.z));
    const float u = p.x - i, v = p.y - j, w = p.z - k;
    float sum = 0;
    for (int c = 0; c < 8; ++c) {
        const int di = c & 1, dj = (c >> 1) & 1, dk = c >> 2;
        sum += (di ? u : 1 - u) * (dj ? v : 1 - v) * (dk ? w : 1 - w) * nvdbtest::value(i + di, j + dj, k + dk);
    }
    return sum;
}

std::string mediumDirective(const std::string& file, const std::string& extra = "") {
    return "MakeNamedMedium \"v\" \"string type\" \"nanovdb\" \"string filename\" \"" + file + "\" " + extra +
           "\n  \"rgb sigma_a\" [ 0.5 0.5 0.5 ] \"rgb sigma_s\" [ 0.5 1 2 ]\n";
}

// The camera in the medium, to reach it through Scene::cameraMedium.
std::string mediumScene(const std::string& file) {
    return mediumDirective(file) + "MediumInterface \"\" \"v\"\nCamera \"perspective\"\nWorldBegin\n";
}

}  // namespace

TEST(NanoVDB, ReaderGivesTheValuesTheToolWrote) {
    for (const char* file : {"tiny.nvdb", "tiny-zip.nvdb"}) {
        SCOPED_TRACE(file);
        std::optional<NanoVDBGrid> g = readNanoVDBGrid(kDir + file, "density");
        ASSERT_TRUE(g);
        int mismatches = 0;
        for (int i = -2; i < 18; ++i)
            for (int j = -2; j < 18; ++j)
                for (int k = -2; k < 18; ++k) mismatches += g->value(i, j, k) != nvdbtest::value(i, j, k);
        EXPECT_EQ(mismatches, 0);
        EXPECT_EQ(g->value(100000, -3, 5), 0.0f);  // no root tile there: the background
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(g->indexMin()[a], 0);
            EXPECT_EQ(g->indexMax()[a], 15);
            EXPECT_FLOAT_EQ(g->worldMin()[a], -0.5f);
            EXPECT_FLOAT_EQ(g->worldMax()[a], 0.5f);
        }
        // The grid before it, one root tile of 0.5 (4096^3 voxels from the origin).
        std::optional<NanoVDBGrid> smoke = readNanoVDBGrid(kDir + file, "smoke");
        ASSERT_TRUE(smoke);
        EXPECT_EQ(smoke->value(4000, 17, 2), 0.5f);
        EXPECT_EQ(smoke->value(4096, 17, 2), 0.0f);
        EXPECT_FALSE(readNanoVDBGrid(kDir + file, "temperature"));
    }
}

TEST(NanoVDB, SamplesTrilinearlyThroughTheGridsMap) {
    std::optional<NanoVDBGrid> g = readNanoVDBGrid(kDir + "tiny.nvdb", "density");
    ASSERT_TRUE(g);
    Rng rng(2);
    for (int n = 0; n < 2000; ++n) {
        const Vec3 pw(rng.uniform() * 1.2f - 0.6f, rng.uniform() * 1.2f - 0.6f, rng.uniform() * 1.2f - 0.6f);
        const Vec3 pi = g->worldToIndex(pw);
        EXPECT_NEAR(pi.x, (pw.x - nvdbtest::kOrigin) / nvdbtest::kVoxelSize, 1e-4f);
        EXPECT_NEAR(g->sample(pi), trilinear(pi), 1e-5f) << pi.x << " " << pi.y << " " << pi.z;
    }
}

TEST(NanoVDB, MajorantGridBoundsTheDensityInEveryCell) {
    auto scene = buildScene(parseSceneString(mediumScene(kDir + "tiny.nvdb"), ".", "<test>"), false);
    const auto* m = dynamic_cast<const NanoVDBMedium*>(scene->cameraMedium());
    ASSERT_TRUE(m);
    const Vec3 e = m->box().p1 - m->box().p0;
    EXPECT_EQ(countCellViolations(m->majorantGrid(), 4, [&](Vec3 p) { return Spectrum(m->density(p)); },
                                  [&](Vec3 u) { return m->box().p0 + Vec3(u.x * e.x, u.y * e.y, u.z * e.z); }),
              0);
    int thin = 0;
    for (float c : m->majorantGrid().cells) thin += c < 1;
    EXPECT_GT(thin, 64 * 64 * 64 / 20) << "the peaky grid should leave many cells far below its maximum of 4";
}

// The bound also holds at points up to 1/8 voxel outside each cell (in index space), where
// rounding may put a collision: there the next ring of voxels weighs up to 1/8 per axis
// (without the ring's share of the bound, points of many cells exceed it).
TEST(NanoVDB, MajorantGridBoundsTheDensityAnEighthOfAVoxelOutsideEachCell) {
    auto scene = buildScene(parseSceneString(mediumScene(kDir + "tiny.nvdb"), ".", "<test>"), false);
    const auto* m = dynamic_cast<const NanoVDBMedium*>(scene->cameraMedium());
    ASSERT_TRUE(m);
    const MajorantGrid& g = m->majorantGrid();
    const Vec3 p0 = m->box().p0, e = m->box().p1 - p0;
    // World units per voxel along each axis, from the grid's own map.
    Vec3 voxel;
    for (int a = 0; a < 3; ++a) {
        Vec3 d(0, 0, 0);
        d[a] = e[a];
        voxel[a] = e[a] / std::abs(m->grid().worldToIndex(p0 + d)[a] - m->grid().worldToIndex(p0)[a]);
    }
    Rng rng(11);
    int bad = 0;
    for (int z = 0; z < g.res[2]; ++z)
        for (int y = 0; y < g.res[1]; ++y)
            for (int x = 0; x < g.res[0]; ++x)
                for (int i = 0; i < 8; ++i) {
                    // A corner of the cell pushed outward by up to 1/8 voxel along each axis.
                    const Vec3 lo = g.cellMin(x, y, z), hi = g.cellMax(x, y, z);
                    Vec3 p;
                    for (int a = 0; a < 3; ++a) {
                        const bool up = (i >> a) & 1;
                        const float push = 0.124f * rng.uniform() * voxel[a];
                        p[a] = p0[a] + (up ? hi[a] : lo[a]) * e[a] + (up ? push : -push);
                    }
                    const float d = m->density(p), bound = g.at(x, y, z);
                    if (d > bound * (1 + 1e-5f) + 1e-6f && bad++ < 5)
                        ADD_FAILURE() << "cell (" << x << "," << y << "," << z << "): density " << d << " > majorant " << bound;
                }
    EXPECT_EQ(bad, 0);
}

// Across the grid's box in x at a height where the peaks are, and diagonally; tau by a
// midpoint rule of 20000 steps inside the box.
TEST(NanoVDB, RatioTrackedTransmittanceIsExpMinusOpticalDepth) {
    auto scene = buildScene(parseSceneString(mediumScene(kDir + "tiny.nvdb"), ".", "<test>"), false);
    const Medium& medium = *scene->cameraMedium();
    const std::pair<Vec3, Vec3> segments[] = {{{-1, 0.1f, -0.2f}, {1, 0.1f, -0.2f}}, {{-0.6f, -0.5f, -0.45f}, {0.5f, 0.6f, 0.45f}}};
    for (const auto& [a, b] : segments) {
        auto inBox = [](Vec3 p) { return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) <= 0.5f; };
        const std::array<double, 3> tau = opticalDepth(medium, a, b, 20000, inBox);
        std::printf("  tau %.4f %.4f %.4f\n", tau[0], tau[1], tau[2]);
        expectTransmittance(ratioTracked(*scene, a, b, 100000), {std::exp(-tau[0]), std::exp(-tau[1]), std::exp(-tau[2])}, "nanovdb");
    }
}

TEST(NanoVDB, BadFilesAreErrorsNamingTheFile) {
    const std::vector<uint8_t> good = fileBytes(kDir + "tiny.nvdb");
    ASSERT_GT(good.size(), 1000u);
    EXPECT_EQ(parseError(good), "");
    // Truncated anywhere: in the header, the metadata, the grids.
    for (size_t cut : {size_t(0), size_t(7), size_t(100), size_t(400), good.size() / 2, good.size() - 1}) {
        const std::string e = parseError(std::vector<uint8_t>(good.begin(), good.begin() + cut));
        if (cut == 0) continue;  // empty: no grid at all, not an error of the reader's
        EXPECT_NE(e.find("bad.nvdb: "), std::string::npos) << cut << ": " << e;
        EXPECT_NE(e.find("truncated"), std::string::npos) << cut << ": " << e;
    }
    auto patched = [&](size_t at, const void* v, size_t n) {
        std::vector<uint8_t> b = good;
        std::memcpy(b.data() + at, v, n);
        return parseError(b);
    };
    const size_t meta2 = 16 + 176 + 6;  // the "density" grid's metadata, after "smoke"'s
    const uint32_t vec3f = 6, levelSet = 1, major31 = 31u << 21;
    const uint16_t blosc = 2;
    EXPECT_NE(patched(0, "NotNanoV", 8).find("not a NanoVDB file"), std::string::npos);
    EXPECT_NE(patched(8, &major31, 4).find("version 31.0 is not supported"), std::string::npos);
    EXPECT_NE(patched(meta2 + 32, &vec3f, 4).find("not float"), std::string::npos) << patched(meta2 + 32, &vec3f, 4);
    EXPECT_NE(patched(meta2 + 36, &levelSet, 4).find("not a fog volume"), std::string::npos);
    EXPECT_NE(patched(14, &blosc, 2).find("Blosc"), std::string::npos);
    // A root tile's child offset pointing outside the grid.
    const size_t grid2 = meta2 + 176 + 8 + (672 + 64 + 64 + 32), rootTile = grid2 + 672 + 64 + 64;
    const int64_t wild = int64_t(1) << 40;
    EXPECT_NE(patched(rootTile + 8, &wild, 8).find("outside the grid"), std::string::npos) << patched(rootTile + 8, &wild, 8);
}

TEST(NanoVDB, BadFilesInScenesAreLocatedErrors) {
    const std::string missing = buildError("WorldBegin\n" + mediumDirective(kDir + "no-such.nvdb"));
    EXPECT_NE(missing.find("scene.pbrt:2:1"), std::string::npos) << missing;
    EXPECT_NE(missing.find("no-such.nvdb: cannot open"), std::string::npos) << missing;
    const std::string noGrid = buildError("WorldBegin\n" + mediumDirective(kDir + "tiny.nvdb", "\"string gridname\" \"fog\""));
    EXPECT_NE(noGrid.find("scene.pbrt:2:1"), std::string::npos) << noGrid;
    EXPECT_NE(noGrid.find("no grid named \"fog\""), std::string::npos) << noGrid;
    // A truncated file on disk.
    const std::string cut = (std::filesystem::temp_directory_path() / "ps-truncated.nvdb").string();
    {
        const std::vector<uint8_t> good = fileBytes(kDir + "tiny.nvdb");
        std::ofstream(cut, std::ios::binary).write(reinterpret_cast<const char*>(good.data()), std::streamsize(good.size() - 5000));
    }
    const std::string t = buildError("WorldBegin\n" + mediumDirective(cut));
    EXPECT_NE(t.find("scene.pbrt:2:1"), std::string::npos) << t;
    EXPECT_NE(t.find(cut + ": truncated"), std::string::npos) << t;
    std::filesystem::remove(cut);
}
