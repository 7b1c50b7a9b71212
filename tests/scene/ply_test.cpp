// PLY reader: small generated files in all three encodings (and gzipped), every error path,
// a mutation fuzz loop, a speed check, and the PLY meshes of the shared pbrt-v4 scenes.
#include "scene/ply.h"
#include "util/memory_limit.h"
#include "shared_data.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

using namespace ps;
namespace fs = std::filesystem;

namespace {

enum class Fmt { Ascii, LE, BE };
const char* formatName(Fmt f) {
    return f == Fmt::Ascii ? "ascii" : f == Fmt::LE ? "binary_little_endian" : "binary_big_endian";
}
const Fmt kFormats[] = {Fmt::Ascii, Fmt::LE, Fmt::BE};
const char* const kTypes[] = {"char",  "uchar",  "short",  "ushort", "int",    "uint",    "float",   "double",
                              "int8",  "uint8",  "int16",  "uint16", "int32",  "uint32",  "float32", "float64"};

template <class T>
void putRaw(std::string& s, double v, bool bigEndian) {
    T x = T(v);
    char b[sizeof(T)];
    std::memcpy(b, &x, sizeof(T));
    if (bigEndian) std::reverse(b, b + sizeof(T));
    s.append(b, sizeof(T));
}

// PLY body writer: one value of a named PLY type at a time, in the chosen encoding.
class Body {
public:
    explicit Body(Fmt f) : fmt_(f) {}
    Body& put(const std::string& type, double v) {
        if (fmt_ == Fmt::Ascii) {
            char buf[40];
            std::snprintf(buf, sizeof buf, "%.17g ", v);
            s_ += buf;
            return *this;
        }
        bool be = fmt_ == Fmt::BE;
        if (type == "char" || type == "int8") putRaw<int8_t>(s_, v, be);
        else if (type == "uchar" || type == "uint8") putRaw<uint8_t>(s_, v, be);
        else if (type == "short" || type == "int16") putRaw<int16_t>(s_, v, be);
        else if (type == "ushort" || type == "uint16") putRaw<uint16_t>(s_, v, be);
        else if (type == "int" || type == "int32") putRaw<int32_t>(s_, v, be);
        else if (type == "uint" || type == "uint32") putRaw<uint32_t>(s_, v, be);
        else if (type == "float" || type == "float32") putRaw<float>(s_, v, be);
        else if (type == "double" || type == "float64") putRaw<double>(s_, v, be);
        else ADD_FAILURE() << "bad type " << type;
        return *this;
    }
    Body& list(const std::string& countType, const std::string& itemType, std::vector<double> items) {
        put(countType, double(items.size()));
        for (double v : items) put(itemType, v);
        return *this;
    }
    Body& nl() {
        if (fmt_ == Fmt::Ascii) s_ += "\n";
        return *this;
    }
    const std::string& str() const { return s_; }

private:
    Fmt fmt_;
    std::string s_;
};

std::string header(Fmt f, const std::string& elements) {
    return std::string("ply\nformat ") + formatName(f) + " 1.0\n" + elements + "end_header\n";
}

class Ply : public ::testing::Test {
protected:
    void SetUp() override {
        setWarningsQuiet(true);
        dir_ = fs::temp_directory_path() / ("pathspace-ply-" + std::to_string(getpid()) + "-" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& bytes) {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
        return (dir_ / name).string();
    }
    std::string writeGz(const std::string& name, const std::string& bytes) {
        std::string path = (dir_ / name).string();
        gzFile f = gzopen(path.c_str(), "wb");
        EXPECT_TRUE(f);
        EXPECT_EQ(gzwrite(f, bytes.data(), unsigned(bytes.size())), int(bytes.size()));
        gzclose(f);
        return path;
    }
    // readPly must throw an InputError naming the file and containing `needle`.
    void expectError(const std::string& name, const std::string& bytes, const std::string& needle) {
        expectErrorAt(write(name, bytes), needle);
    }
    void expectErrorAt(const std::string& path, const std::string& needle) {
        try {
            readPly(path);
            ADD_FAILURE() << "no error for " << path << " (expected \"" << needle << "\")";
        } catch (const InputError& e) {
            std::string m = e.what();
            EXPECT_EQ(m.rfind(path + ": ", 0), 0u) << m;
            EXPECT_NE(m.find(needle), std::string::npos) << "expected \"" << needle << "\" in: " << m;
        }
    }
    fs::path dir_;
};

// A mesh that exercises everything the reader keeps and skips: an unknown element before and
// after the mesh, unknown scalar and list properties, double positions, normals, s/t uv, a
// triangle, a quad and a pentagon (skipped), uint8/uint32 index lists and face_indices.
std::string sampleMesh(Fmt f) {
    std::string h = header(f,
                           "comment made by hand\nobj_info nothing\n"
                           "element material 2\nproperty list uint8 float weights\nproperty int id\n"
                           "element vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
                           "property uchar red\nproperty float nx\nproperty float ny\nproperty float nz\n"
                           "property list ushort short junk\nproperty float s\nproperty float t\n"
                           "element face 3\nproperty list uint8 uint32 vertex_indices\nproperty int face_indices\n"
                           "property list uint int16 tags\n"
                           "element edge 1\nproperty int16 a\nproperty list int8 float64 b\n");
    Body b(f);
    b.list("uint8", "float", {0.5, 0.25, 2}).put("int", 7).nl();
    b.list("uint8", "float", {}).put("int", -7).nl();
    for (int i = 0; i < 5; ++i) {
        b.put("double", i + 0.125).put("double", 2 * i).put("double", -i).put("uchar", 200);
        b.put("float", 0).put("float", 0).put("float", 1);
        b.list("ushort", "short", {-1, 2}).put("float", 0.25 * i).put("float", 1 - 0.25 * i).nl();
    }
    b.list("uint8", "uint32", {0, 1, 2}).put("int", 10).list("uint", "int16", {}).nl();
    b.list("uint8", "uint32", {0, 1, 2, 3}).put("int", 11).list("uint", "int16", {5, 6, 7}).nl();
    b.list("uint8", "uint32", {0, 1, 2, 3, 4}).put("int", 12).list("uint", "int16", {9}).nl();
    b.put("int16", 3).list("int8", "float64", {1, 2}).nl();
    return h + b.str();
}

void expectSampleMesh(const PlyMesh& m) {
    ASSERT_EQ(m.P.size(), 5u);
    ASSERT_EQ(m.N.size(), 5u);
    ASSERT_EQ(m.uv.size(), 5u);
    EXPECT_FLOAT_EQ(m.P[3].x, 3.125f);
    EXPECT_FLOAT_EQ(m.P[3].y, 6.0f);
    EXPECT_FLOAT_EQ(m.P[3].z, -3.0f);
    EXPECT_FLOAT_EQ(m.N[4].z, 1.0f);
    EXPECT_FLOAT_EQ(m.uv[2].x, 0.5f);
    EXPECT_FLOAT_EQ(m.uv[2].y, 0.5f);
    EXPECT_EQ(m.triIndices, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(m.quadIndices, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_EQ(m.faceIndices, (std::vector<int>{10, 11, 12}));
}

}  // namespace

TEST_F(Ply, AllFormatsReadTheSameMeshAndSkipUnknowns) {
    for (Fmt f : kFormats) {
        SCOPED_TRACE(formatName(f));
        int before = warningCount();
        PlyMesh m = readPly(write(std::string(formatName(f)) + ".ply", sampleMesh(f)));
        expectSampleMesh(m);
        EXPECT_EQ(warningCount(), before + 1);  // the pentagon
    }
}

TEST_F(Ply, AsciiTrianglesAndQuadsWithFreeLayout) {
    // CRLF lines, tabs, a leading '+', exponents, and a vertex split over two lines.
    std::string s =
        "ply\r\nformat ascii 1.0\r\ncomment x\r\nelement vertex 4\r\nproperty float x\r\nproperty float y\r\n"
        "property float z\r\nproperty float u\r\nproperty float v\r\nelement face 2\r\n"
        "property list uchar int vertex_indices\r\nend_header\r\n"
        "0 0 0 0 0\r\n1e0\t0 0 1 0\r\n+1 1 0\r\n 1 1\r\n0 1 -0.5e-1 0 1\r\n3 0 1 2\r\n4 0 1 2 3";  // no final newline
    PlyMesh m = readPly(write("a.ply", s));
    ASSERT_EQ(m.P.size(), 4u);
    EXPECT_TRUE(m.N.empty());
    EXPECT_TRUE(m.faceIndices.empty());
    EXPECT_FLOAT_EQ(m.P[1].x, 1.0f);
    EXPECT_FLOAT_EQ(m.P[2].x, 1.0f);
    EXPECT_FLOAT_EQ(m.P[3].z, -0.05f);
    EXPECT_FLOAT_EQ(m.uv[2].y, 1.0f);
    EXPECT_EQ(m.triIndices, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(m.quadIndices, (std::vector<int>{0, 1, 2, 3}));
}

TEST_F(Ply, EveryScalarTypeForPropertiesAndLists) {
    for (Fmt f : kFormats)
        for (const char* t : kTypes) {
            std::string type = t;
            SCOPED_TRACE(std::string(formatName(f)) + " " + type);
            // An unknown property of the type first, so a wrong size shifts everything after it.
            std::string h = header(f, "element vertex 3\nproperty " + type + " skipme\nproperty " + type + " x\nproperty " +
                                          type + " y\nproperty " + type + " z\nelement face 1\nproperty list " + type + " " +
                                          type + " vertex_indices\nproperty list " + type + " " + type + " other\n");
            Body b(f);
            for (int i = 0; i < 3; ++i) b.put(type, 100).put(type, i).put(type, 2 * i).put(type, 3 - i).nl();
            b.list(type, type, {2, 0, 1}).list(type, type, {1, 2, 3, 4, 5}).nl();
            PlyMesh m = readPly(write("t.ply", h + b.str()));
            ASSERT_EQ(m.P.size(), 3u);
            EXPECT_FLOAT_EQ(m.P[2].x, 2.0f);
            EXPECT_FLOAT_EQ(m.P[2].y, 4.0f);
            EXPECT_FLOAT_EQ(m.P[2].z, 1.0f);
            EXPECT_EQ(m.triIndices, (std::vector<int>{2, 0, 1}));
        }
}

TEST_F(Ply, UvNamesNormalsAndPriority) {
    auto read = [&](const std::string& props, const std::string& values) {
        return readPly(write("uv.ply", header(Fmt::Ascii, "element vertex 1\nproperty float x\nproperty float y\n"
                                                          "property float z\n" + props) + "0 0 0 " + values + "\n"));
    };
    for (auto [u, v] : {std::pair{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}}) {
        PlyMesh m = read(std::string("property float ") + u + "\nproperty float " + v + "\n", "0.25 0.75");
        ASSERT_EQ(m.uv.size(), 1u) << u;
        EXPECT_FLOAT_EQ(m.uv[0].x, 0.25f);
        EXPECT_FLOAT_EQ(m.uv[0].y, 0.75f);
    }
    // u v wins over s t, whatever the order in the file.
    PlyMesh m = read("property float s\nproperty float t\nproperty float u\nproperty float v\n", "1 2 3 4");
    ASSERT_EQ(m.uv.size(), 1u);
    EXPECT_FLOAT_EQ(m.uv[0].x, 3.0f);
    // Incomplete pairs and normals are ignored.
    m = read("property float u\nproperty float t\nproperty float nx\nproperty float ny\n", "1 2 3 4");
    EXPECT_TRUE(m.uv.empty());
    EXPECT_TRUE(m.N.empty());
    EXPECT_EQ(m.P.size(), 1u);
}

TEST_F(Ply, GzipDetectedByMagicOrSuffix) {
    for (Fmt f : kFormats) {
        SCOPED_TRACE(formatName(f));
        expectSampleMesh(readPly(writeGz("magic.ply", sampleMesh(f))));
        expectSampleMesh(readPly(writeGz("suffix.ply.gz", sampleMesh(f))));
    }
    // A ".gz" name on an uncompressed file still reads (zlib passes it through).
    expectSampleMesh(readPly(write("plain.ply.gz", sampleMesh(Fmt::LE))));
}

TEST_F(Ply, PentagonSkippedWithOneWarning) {
    std::string s = header(Fmt::Ascii, "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                                       "element face 4\nproperty list uchar int vertex_indices\n") +
                    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 0\n5 0 1 2 3 4\n3 0 1 2\n5 4 3 2 1 0\n2 0 1\n";
    int before = warningCount();
    PlyMesh m = readPly(write("penta.ply", s));
    EXPECT_EQ(warningCount(), before + 1);
    EXPECT_EQ(m.triIndices, (std::vector<int>{0, 1, 2}));
    EXPECT_TRUE(m.quadIndices.empty());
}

TEST_F(Ply, VertexIndexAcceptedWithWarning) {
    std::string s = header(Fmt::Ascii, "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                       "element face 2\nproperty list uchar int vertex_index\n") +
                    "0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n3 2 1 0\n";
    int before = warningCount();
    PlyMesh m = readPly(write("vi.ply", s));
    EXPECT_EQ(warningCount(), before + 1);
    EXPECT_EQ(m.triIndices, (std::vector<int>{0, 1, 2, 2, 1, 0}));
}

TEST_F(Ply, EmptyAndFacelessMeshesAreNotErrors) {
    PlyMesh m = readPly(write("e.ply", header(Fmt::LE, "element vertex 0\nproperty float x\nproperty float y\n"
                                                       "property float z\nelement face 0\n"
                                                       "property list uchar int vertex_indices\n")));
    EXPECT_TRUE(m.P.empty());
    m = readPly(write("p.ply", header(Fmt::Ascii, "element vertex 1\nproperty float x\nproperty float y\n"
                                                  "property float z\n") + "1 2 3\n"));
    EXPECT_EQ(m.P.size(), 1u);
    EXPECT_TRUE(m.triIndices.empty());
}

TEST_F(Ply, FileErrors) {
    expectErrorAt((dir_ / "missing.ply").string(), "cannot open");
    expectErrorAt(dir_.string(), "not a regular file");
    std::string gz = sampleMesh(Fmt::LE);
    std::string good = (dir_ / "good.ply.gz").string();
    writeGz("good.ply.gz", gz);
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    expectError("cut.ply.gz", bytes.substr(0, bytes.size() / 2), "corrupt gzip");
    std::string junk = bytes;
    for (size_t i = 20; i < junk.size() - 8; i += 7) junk[i] = char(junk[i] ^ 0x5a);
    expectError("junk.ply", junk, "gzip");
}

TEST_F(Ply, HeaderErrors) {
    const std::string xyz = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
    expectError("empty.ply", "", "not a PLY file");
    expectError("magic.ply", "plx\nformat ascii 1.0\nend_header\n", "not a PLY file");
    expectError("magic2.ply", "ply2\n", "not a PLY file");
    expectError("noend.ply", "ply\nformat ascii 1.0\n" + xyz, "no end_header");
    expectError("noformat.ply", "ply\n" + xyz + "end_header\n0 0 0\n", "no format line");
    expectError("format.ply", "ply\nformat binary_middle_endian 1.0\n" + xyz + "end_header\n", "unsupported PLY format");
    expectError("version.ply", "ply\nformat ascii 2.0\n" + xyz + "end_header\n", "unsupported PLY version");
    expectError("keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 1\nend_header\n", "bad PLY header line 3");
    expectError("early.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", "bad PLY header line 3");
    expectError("short.ply", "ply\nformat ascii 1.0\nelement vertex\nend_header\n", "bad PLY header line");
    expectError("listarity.ply", "ply\nformat ascii 1.0\n" + xyz + "property list uchar idx\nend_header\n",
                "bad PLY header line");
    expectError("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n",
                "unknown PLY property type \"real\"");
    expectError("ltype.ply", "ply\nformat ascii 1.0\n" + xyz + "property list long int a\nend_header\n",
                "unknown PLY property type \"long\"");
    expectError("neg.ply", "ply\nformat ascii 1.0\nelement vertex -5\nend_header\n", "bad element count");
    expectError("huge.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nend_header\n",
                "bad element count");
    expectError("dup.ply", "ply\nformat ascii 1.0\n" + xyz + xyz + "end_header\n", "more than one \"vertex\"");
    expectError("novertex.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n", "no vertex element");
    expectError("noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n",
                "no \"z\" property");
    expectError("listx.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\nproperty float y\n"
                             "property float z\nend_header\n",
                "\"x\" is a list");
    expectError("noidx.ply", "ply\nformat ascii 1.0\n" + xyz + "element face 1\nproperty int a\nend_header\n0 0 0\n1\n",
                "no \"vertex_indices\"");
    expectError("scalaridx.ply", "ply\nformat ascii 1.0\n" + xyz + "element face 1\nproperty int vertex_indices\nend_header\n",
                "is a number, not a list");
    expectError("toomany.ply", "ply\nformat ascii 1.0\nelement vertex 3000000000\nproperty float x\nproperty float y\n"
                               "property float z\nend_header\n",
                "too many vertices");
}

TEST_F(Ply, AbsurdCountsFailFastWithoutAllocating) {
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const std::string idx = "element face 2000000000\nproperty list uchar int vertex_indices\n";
    std::string verts;
    for (int i = 0; i < 9; ++i) putRaw<float>(verts, i, false);
    expectError("v.ply", header(Fmt::LE, "element vertex 1000000000\n" + xyz) + verts,
                "truncated binary PLY: expected 1000000000 vertices, got 3");
    std::string face;
    putRaw<uint8_t>(face, 3, false);
    for (int i = 0; i < 3; ++i) putRaw<int32_t>(face, i, false);
    expectError("f.ply", header(Fmt::LE, "element vertex 3\n" + xyz + idx) + verts + face,
                "truncated binary PLY: expected 2000000000 faces, got 1");
    expectError("u.ply", header(Fmt::BE, "element blob 2000000000000\nproperty list uint uint x\nelement vertex 0\n" + xyz),
                "truncated binary PLY: expected 2000000000000 \"blob\" elements, got 0");
    expectError("a.ply", header(Fmt::Ascii, "element vertex 300000000\n" + xyz) + "0 0 0\n", "exceeds the limit of 2^28");
    expectError("a2.ply", header(Fmt::Ascii, "element vertex 200000000\n" + xyz) + "0 0 0\n",
                "truncated ASCII PLY: expected 200000000 vertices, got 1");
    // An element without properties takes no bytes, whatever its count.
    PlyMesh m = readPly(write("empty-elem.ply", header(Fmt::LE, "element nothing 18000000000000000000\n"
                                                                "element vertex 3\n" + xyz) + verts));
    EXPECT_EQ(m.P.size(), 3u);
}

// A mesh whose data is all there but needs more memory than the limit fails before its arrays
// are sized; a header claiming more than the file holds still fails as truncated.
TEST_F(Ply, MeshBeyondTheMemoryLimit) {
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    ScopedMemoryLimit limit(4096);
    for (Fmt f : kFormats) {
        SCOPED_TRACE(formatName(f));
        Body b(f);
        for (int i = 0; i < 1000; ++i) b.put("float", i).put("float", 0).put("float", 1).nl();
        expectError("big.ply", header(f, "element vertex 1000\n" + xyz) + b.str(),
                    "a mesh of 1000 vertices needs 11.7 KiB of memory, more than the limit of 4.0 KiB "
                    "(raise it with --max-memory)");
        Body faces(f);
        for (int i = 0; i < 3; ++i) faces.put("float", i).put("float", 0).put("float", 1).nl();
        for (int i = 0; i < 400; ++i) faces.list("uchar", "int", {0, 1, 2}).nl();
        expectError("faces.ply", header(f, "element vertex 3\n" + xyz + "element face 400\nproperty list uchar int "
                                           "vertex_indices\n") + faces.str(),
                    "a mesh of 400 faces needs 4.7 KiB of memory");
    }
    std::string verts;
    for (int i = 0; i < 9; ++i) putRaw<float>(verts, i, false);
    expectError("claim.ply", header(Fmt::LE, "element vertex 1000000000\n" + xyz) + verts,
                "truncated binary PLY: expected 1000000000 vertices, got 3");
    setMemoryLimit(limit.saved());
    expectError("claim.ply", header(Fmt::LE, "element vertex 1000000000\n" + xyz) + verts,
                "truncated binary PLY: expected 1000000000 vertices, got 3");
}

TEST_F(Ply, TruncatedData) {
    const std::string h = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                          "element face 2\nproperty list uchar int vertex_indices\n";
    for (Fmt f : kFormats) {
        SCOPED_TRACE(formatName(f));
        const char* kind = f == Fmt::Ascii ? "ASCII" : "binary";
        Body b(f);
        for (int i = 0; i < 3; ++i) b.put("float", i).put("float", 0).put("float", 1).nl();
        b.list("uchar", "int", {0, 1, 2}).nl();
        std::string full = header(f, h) + b.str();
        if (f != Fmt::Ascii) {
            expectError("v.ply", header(f, h) + b.str().substr(0, 30), std::string("truncated ") + kind +
                                                                            " PLY: expected 3 vertices, got 2");
        } else {
            expectError("v.ply", header(f, h) + "0 0 1\n1 0 1\n2 0", "truncated ASCII PLY: expected 3 vertices, got 2");
        }
        expectError("f.ply", full, std::string("truncated ") + kind + " PLY: expected 2 faces, got 1");
        // Cut inside the second face's list.
        b.put("uchar", 3).put("int", 0);
        expectError("g.ply", header(f, h) + b.str(), std::string("truncated ") + kind + " PLY: expected 2 faces, got 1");
    }
}

TEST_F(Ply, BadIndicesAndListCounts) {
    const std::string xyz = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    for (Fmt f : kFormats) {
        SCOPED_TRACE(formatName(f));
        auto withFace = [&](const std::string& countType, const std::string& itemType, std::vector<double> items,
                            double count) {
            Body b(f);
            for (int i = 0; i < 3; ++i) b.put("float", i).put("float", 0).put("float", 0).nl();
            b.put(countType, count);
            for (double v : items) b.put(itemType, v);
            return header(f, xyz + "element face 1\nproperty list " + countType + " " + itemType + " vertex_indices\n") +
                   b.str();
        };
        expectError("r1.ply", withFace("uchar", "int", {0, 1, 3}, 3), "vertex index 3 out of range [0, 3)");
        expectError("r2.ply", withFace("uchar", "int", {0, -1, 2}, 3), "vertex index -1 out of range [0, 3)");
        expectError("r3.ply", withFace("uchar", "uint", {0, 1, 4294967295.0, 2}, 4), "out of range [0, 3)");
        expectError("r4.ply", withFace("uchar", "float", {0, 1.5, 2}, 3), "non-integer vertex index 1.5");
        expectError("c1.ply", withFace("char", "int", {}, -1), "bad list length -1");
        expectError("c2.ply", withFace("int", "int", {}, 70000), "bad list length 70000");
        expectError("c3.ply", withFace("uint", "uchar", {}, 4000000000.0), "bad list length 4000000000");
    }
    // Lists of unknown properties and elements are checked too.
    expectError("c4.ply", header(Fmt::Ascii, "element junk 1\nproperty list int int a\n" + xyz) + "-3\n", "bad list length -3");
    expectError("c5.ply", header(Fmt::Ascii, xyz) + "0 0 0\n1 x 0\n", "bad number \"x\" in ASCII PLY data on line 9");
    expectError("c6.ply", header(Fmt::Ascii, xyz + "element face 1\nproperty list uchar int vertex_indices\n"
                                                   "property float face_indices\n") +
                              "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.5\n",
                "bad face_indices value 0.5");
}

TEST_F(Ply, NonFiniteValuesRejected) {
    const std::string h = "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                          "property float nx\nproperty float ny\nproperty float nz\n";
    auto file = [&](Fmt f, std::vector<float> second) {
        Body b(f);
        for (int i = 0; i < 6; ++i) b.put("float", 0);
        b.nl();
        for (float v : second) b.put("float", v);
        return header(f, h) + b.str();
    };
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (Fmt f : kFormats) {
        SCOPED_TRACE(formatName(f));
        expectError("n1.ply", file(f, {0, nan, 0, 0, 0, 1}), "vertex 1 has a non-finite position value nan");
        expectError("n2.ply", file(f, {0, 0, -inf, 0, 0, 1}), "vertex 1 has a non-finite position value -inf");
        expectError("n3.ply", file(f, {0, 0, 0, nan, 0, 1}), "vertex 1 has a non-finite normal");
    }
    // Finite in the file but beyond float: a double, and ASCII text.
    std::string d;
    for (double v : {1e300, 0.0, 0.0}) putRaw<double>(d, v, false);
    expectError("d.ply", header(Fmt::LE, "element vertex 1\nproperty double x\nproperty double y\nproperty double z\n") + d,
                "vertex 0 has an out-of-range position value 1e+300");
    expectError("t.ply", header(Fmt::Ascii, h) + "0 0 0 0 0 1\n1e39 0 0 0 0 1\n", "out-of-range position value 1e+39");
    expectError("t2.ply", header(Fmt::Ascii, h) + "0 0 0 0 0 1\n1e999 0 0 0 0 1\n", "non-finite position value inf");
    // Tiny values underflow to zero rather than failing.
    PlyMesh m = readPly(write("tiny.ply", header(Fmt::Ascii, h) + "0 0 0 0 0 1\n1e-999 0 0 0 0 1\n"));
    EXPECT_EQ(m.P[1].x, 0.0f);
}

// Truncations and random byte flips of valid files: every outcome is a mesh or an InputError.
TEST_F(Ply, MutatedFilesNeverCrash) {
    std::mt19937 rng(1234);
    int errors = 0, meshes = 0;
    auto attempt = [&](const std::string& bytes) {
        std::string path = write("fuzz.ply", bytes);
        try {
            PlyMesh m = readPly(path);
            for (int i : m.triIndices) ASSERT_TRUE(i >= 0 && size_t(i) < m.P.size());
            for (int i : m.quadIndices) ASSERT_TRUE(i >= 0 && size_t(i) < m.P.size());
            ASSERT_TRUE(m.N.empty() || m.N.size() == m.P.size());
            ASSERT_TRUE(m.uv.empty() || m.uv.size() == m.P.size());
            ++meshes;
        } catch (const InputError&) {
            ++errors;
        }
    };
    for (Fmt f : kFormats) {
        const std::string good = sampleMesh(f);
        for (size_t n = 0; n < good.size(); ++n) attempt(good.substr(0, n));
        for (int i = 0; i < 800; ++i) {
            std::string s = good;
            int flips = 1 + int(rng() % 4);
            for (int k = 0; k < flips; ++k) {
                size_t at = rng() % s.size();
                s[at] = (rng() % 2) ? char(rng()) : "0123456789 \n-e.x"[rng() % 16];
            }
            attempt(s);
        }
    }
    EXPECT_GT(errors, 0);
    EXPECT_GT(meshes, 0);
}

// Load time is a benchmark, not a test: only the result is checked here.
TEST_F(Ply, MillionTriangleBinaryMesh) {
    const int n = 708;  // grid of n x n vertices: 2 (n-1)^2 ≈ 1M triangles
    std::string s = header(Fmt::LE, "element vertex " + std::to_string(n * n) +
                                        "\nproperty float x\nproperty float y\nproperty float z\n"
                                        "element face " + std::to_string(2 * (n - 1) * (n - 1)) +
                                        "\nproperty list uchar int vertex_indices\n");
    s.reserve(s.size() + size_t(n) * n * 12 + size_t(n) * n * 26);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            for (float v : {float(i), float(j), 0.0f}) putRaw<float>(s, v, false);
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            int a = j * n + i;
            int tris[2][3] = {{a, a + 1, a + n + 1}, {a, a + n + 1, a + n}};
            for (const auto& t : tris) {
                putRaw<uint8_t>(s, 3, false);
                for (int v : t) putRaw<int32_t>(s, v, false);
            }
        }
    std::string path = write("big.ply", s);
    PlyMesh m = readPly(path);
    EXPECT_EQ(m.P.size(), size_t(n) * n);
    EXPECT_EQ(m.triIndices.size(), size_t(6 * (n - 1) * (n - 1)));
    EXPECT_EQ(m.triIndices[5], n);
}

TEST_F(Ply, SharedSceneMeshes) {
    const fs::path shared = fs::path(PATHSPACE_SHARED_DIR) / "scenes";
    REQUIRE_SHARED_DATA(shared);
    auto check = [](const fs::path& f) {
        SCOPED_TRACE(f.string());
        PlyMesh m = readPly(f.string());
        EXPECT_FALSE(m.P.empty());
        EXPECT_GT(m.triIndices.size() + m.quadIndices.size(), 0u);
        EXPECT_TRUE(m.N.empty() || m.N.size() == m.P.size());
        EXPECT_TRUE(m.uv.empty() || m.uv.size() == m.P.size());
        return m;
    };
    int files = 0;
    for (const char* dir : {"veach-bidir/models", "veach-ajar/models"}) {
        if (!fs::exists(shared / dir)) continue;
        for (const auto& entry : fs::directory_iterator(shared / dir))
            if (entry.path().extension() == ".ply") {
                check(entry.path());
                ++files;
            }
    }
    EXPECT_GT(files, 0);
    if (fs::exists(shared / "veach-bidir/models/Mesh000.ply")) {
        PlyMesh m = check(shared / "veach-bidir/models/Mesh000.ply");
        EXPECT_EQ(m.P.size(), 24u);
        EXPECT_EQ(m.uv.size(), 24u);
        EXPECT_EQ(m.triIndices.size(), 36u);
    }
    fs::path glass = shared / "caustic-glass/geometry/mesh_00001.ply";
    if (fs::exists(glass)) {
        PlyMesh m = check(glass);
        EXPECT_EQ(m.P.size(), 44034u);
        EXPECT_EQ(m.N.size(), 44034u);
        EXPECT_TRUE(m.uv.empty());
        EXPECT_EQ(m.triIndices.size(), 3u * 88064u);
        EXPECT_TRUE(m.quadIndices.empty());
    }
}
