#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "scene/ply.h"
#include "util/error.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

class Ply : public ::testing::Test {
protected:
    void SetUp() override {
        setWarningsQuiet(true);
        dir = fs::temp_directory_path() / ("pathspace-ply-" + std::to_string(getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string write(const std::string& name, const std::string& bytes) {
        std::ofstream(dir / name, std::ios::binary) << bytes;
        return (dir / name).string();
    }
    fs::path dir;
};

template <typename T>
void put(std::string& s, T v, bool bigEndian = false) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (bigEndian) std::reverse(b, b + sizeof(T));
    s.append(b, sizeof(T));
}

void expectError(const std::string& path, const std::string& needle) {
    try {
        readPly(path);
        ADD_FAILURE() << "no error for " << path;
    } catch (const InputError& e) {
        std::string m = e.what();
        EXPECT_NE(m.find(fs::path(path).filename().string()), std::string::npos) << m;
        EXPECT_NE(m.find(needle), std::string::npos) << m;
    }
}

}  // namespace

TEST_F(Ply, AsciiTrianglesQuadsAndSkippedPolygons) {
    std::string p = write("a.ply",
                          "ply\nformat ascii 1.0\ncomment hi\nelement vertex 5\nproperty float x\nproperty float y\n"
                          "property float z\nproperty float u\nproperty float v\nproperty float extra\n"
                          "element face 3\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0 0 0 9\n1 0 0 1 0 9\n1 1 0 1 1 9\n0 1 0 0 1 9\n2 2 2 0.5 0.5 9\n"
                          "3 0 1 2\n4 0 1 2 3\n5 0 1 2 3 4\n");
    PlyMesh m = readPly(p);
    EXPECT_EQ(m.P.size(), 5u);
    EXPECT_EQ(m.uv.size(), 5u);
    EXPECT_TRUE(m.N.empty());
    EXPECT_EQ(m.triIndices, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(m.quadIndices, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_FLOAT_EQ(m.P[4].z, 2.0f);
}

TEST_F(Ply, BinaryBothEndiannessesAndUnknownElements) {
    for (bool be : {false, true}) {
        std::string s = std::string("ply\nformat ") + (be ? "binary_big_endian" : "binary_little_endian") +
                        " 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                        "property float nx\nproperty float ny\nproperty float nz\n"
                        "element material 1\nproperty list uchar float stuff\n"
                        "element face 1\nproperty list uint8 uint32 vertex_indices\nproperty int face_indices\nend_header\n";
        for (int v = 0; v < 3; ++v) {
            put<double>(s, v, be);
            put<double>(s, 2 * v, be);
            put<double>(s, -v, be);
            put<float>(s, 0, be);
            put<float>(s, 0, be);
            put<float>(s, 1, be);
        }
        put<uint8_t>(s, 2);
        put<float>(s, 1, be);
        put<float>(s, 2, be);
        put<uint8_t>(s, 3);
        for (uint32_t i : {2u, 1u, 0u}) put<uint32_t>(s, i, be);
        put<int32_t>(s, 7, be);
        PlyMesh m = readPly(write(be ? "be.ply" : "le.ply", s));
        ASSERT_EQ(m.P.size(), 3u);
        EXPECT_FLOAT_EQ(m.P[2].y, 4.0f);
        EXPECT_FLOAT_EQ(m.N[1].z, 1.0f);
        EXPECT_EQ(m.triIndices, (std::vector<int>{2, 1, 0}));
        EXPECT_EQ(m.faceIndices, (std::vector<int>{7}));
    }
}

TEST_F(Ply, Gzipped) {
    std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    std::string path = (dir / "g.ply.gz").string();
    gzFile f = gzopen(path.c_str(), "wb");
    gzwrite(f, text.data(), unsigned(text.size()));
    gzclose(f);
    EXPECT_EQ(readPly(path).triIndices.size(), 3u);
}

TEST_F(Ply, BadFilesGiveClearErrors) {
    expectError((dir / "missing.ply").string(), "cannot open");
    expectError(write("notply.ply", "hello\n"), "not a PLY");
    expectError(write("noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n"), "x, y or z");
    std::string hdr = "ply\nformat binary_little_endian 1.0\nelement vertex 1000000\nproperty float x\nproperty float y\n"
                      "property float z\nend_header\n";
    expectError(write("trunc.ply", hdr + std::string(24, '\0')), "truncated");
    expectError(write("range.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                    "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
                "out of range");
    expectError(write("neg.ply", "ply\nformat ascii 1.0\nelement vertex -5\nend_header\n"), "count");
    expectError(write("nan.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                  "property float z\nend_header\nnan 0 0\n"),
                "non-finite");
}

TEST_F(Ply, SharedSceneMeshes) {
    fs::path f = fs::path(PATHSPACE_SHARED_DIR) / "scenes/caustic-glass/geometry/mesh_00001.ply";
    if (!fs::exists(f)) GTEST_SKIP();
    PlyMesh m = readPly(f.string());
    EXPECT_GT(m.triIndices.size() / 3 + m.quadIndices.size() / 4, 80000u);
    EXPECT_EQ(m.N.size(), m.P.size());
}
