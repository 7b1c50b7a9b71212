// Bad input must give an InputError naming the file, never a crash or a huge allocation.
#include <OpenEXR/ImfRgbaFile.h>
#include <stb/stb_image_write.h>

#include <cstring>
#include <random>

#include "image/image_test_util.h"
#include "image/png_builder.h"
#include "util/memory_limit.h"

using namespace ps;
using namespace ps::test;
namespace fs = std::filesystem;

namespace {

using ImageErrors = TempDirTest;

}  // namespace

TEST_F(ImageErrors, MissingFileAndDirectory) {
    expectInputError([&] { readImage(path("wood.tga")); },
                     {path("wood.tga") + ": cannot open image: No such file or directory"});
    fs::create_directories(dir / "folder.png");
    expectInputError([&] { readImage(path("folder.png")); }, {"folder.png", "directory"});
}

TEST_F(ImageErrors, NotAnImage) {
    writeBytes("text.png", "this is not an image\n");
    expectInputError([&] { readImage(path("text.png")); }, {"text.png: not a readable image (stb: "});
    writeBytes("empty.jpg", "");
    expectInputError([&] { readImage(path("empty.jpg")); }, {"empty.jpg"});
    writeBytes("bad.exr", "nope");
    expectInputError([&] { readImage(path("bad.exr")); }, {"bad.exr"});
    writeBytes("bad.pfm", "P6\n1 1\n255\nabc");
    expectInputError([&] { readImage(path("bad.pfm")); }, {"bad.pfm", "not a PFM file"});
}

TEST_F(ImageErrors, BadPfmHeaders) {
    writeBytes("short.pfm", "PF\n100 100\n-1\nabc");
    expectInputError([&] { readImage(path("short.pfm")); }, {"short.pfm: truncated PFM data"});
    writeBytes("nodata.pfm", "PF\n1 1\n-1\n");
    expectInputError([&] { readImage(path("nodata.pfm")); }, {"nodata.pfm: truncated PFM data"});
    writeBytes("huge.pfm", "PF\n1000000 1000000\n-1\n");
    expectInputError([&] { readImage(path("huge.pfm")); }, {"huge.pfm", "out of range"});
    writeBytes("overflow.pfm", "PF\n4294967296 4294967296\n-1\n");  // w*h wraps to 0 in 64 bits
    expectInputError([&] { readImage(path("overflow.pfm")); }, {"overflow.pfm", "out of range"});
    writeBytes("toolong.pfm", "PF\n99999999999999999999999 2\n-1\n");
    expectInputError([&] { readImage(path("toolong.pfm")); }, {"toolong.pfm", "bad PFM header"});
    writeBytes("negative.pfm", "PF\n-3 2\n-1\n" + std::string(100, '\0'));
    expectInputError([&] { readImage(path("negative.pfm")); }, {"negative.pfm", "out of range"});
    writeBytes("zero.pfm", "PF\n0 2\n-1\n");
    expectInputError([&] { readImage(path("zero.pfm")); }, {"zero.pfm", "out of range"});
    writeBytes("words.pfm", "PF\nwide tall\n-1\n");
    expectInputError([&] { readImage(path("words.pfm")); }, {"words.pfm", "bad PFM header"});
    for (const char* scale : {"0", "nan", "inf", "x"}) {
        writeBytes("scale.pfm", "PF\n1 1\n" + std::string(scale) + "\n" + std::string(12, '\0'));
        expectInputError([&] { readImage(path("scale.pfm")); }, {"scale.pfm", "scale"});
    }
}

TEST_F(ImageErrors, HugePngHeaderIsRejectedBeforeDecoding) {
    // 2^29 grey pixels: within stb's own limit (2^30 bytes), beyond ours.
    writeBytes("huge.png", pngSignatureAndHeader(32768, 16384, 8, 0));
    expectInputError([&] { readImage(path("huge.png")); }, {"huge.png", "out of range"});
    // Within both limits, but no real file of a few dozen bytes holds 2^26 pixels.
    writeBytes("small.png", pngSignatureAndHeader(8192, 8192, 8, 2));
    expectInputError([&] { readImage(path("small.png")); }, {"small.png", "implausible"});
    // stb itself refuses this one, with a less specific message.
    writeBytes("huger.png", pngSignatureAndHeader(65536, 65536, 8, 2));
    expectInputError([&] { readImage(path("huger.png")); }, {"huger.png: not a readable image"});
}

// A valid image that would need more memory than the limit fails before decoding, with both
// sizes; the default limit reads it.
TEST_F(ImageErrors, ImageBeyondTheMemoryLimit) {
    writeImage(path("big.pfm"), testPattern(256, 256));
    writeImage(path("big.png"), testPattern(256, 256));
    ScopedMemoryLimit limit(64 * 1024);
    for (const char* name : {"big.pfm", "big.png"})
        expectInputError([&] { readImage(path(name)); },
                         {path(name) + ": image 256x256 needs 1.0 MiB of memory, more than the limit of 64.0 KiB "
                                       "(raise it with --max-memory)"});
    setMemoryLimit(limit.saved());
    EXPECT_EQ(readImage(path("big.png")).width, 256);
}

// stb sizes its buffer for a PNG's image data by each IDAT chunk's declared length: a chunk
// that declares more bytes than the file holds is refused before stb allocates them (a fuzzed
// 117-byte file made it allocate 2 GiB).
TEST_F(ImageErrors, PngChunkLongerThanTheFile) {
    std::string png = pngSignatureAndHeader(3, 2, 16, 0);
    putBE32(png, 0x7ffffff0u);
    png += "IDAT";
    png += std::string(40, '\x01');
    writeBytes("c.png", png);
    expectInputError([&] { readImage(path("c.png")); },
                     {"c.png: corrupt PNG: chunk \"IDAT\" declares 2147483632 bytes, but only"});
    // A well-formed file still reads.
    writeImage(path("ok.png"), testPattern(8, 8));
    EXPECT_EQ(readImage(path("ok.png")).width, 8);
}

// Formats stb_image knows but pathspace does not offer are refused by name, before stb's
// decoder for them runs (a fuzzed PNM header overflowed its integer parser).
TEST_F(ImageErrors, UndocumentedStbFormatsAreRefused) {
    writeBytes("a.tga", "P5 0000007440229401258739 2 255\n");
    expectInputError([&] { readImage(path("a.tga")); }, {"a.tga: PNM (PGM/PPM) images are not supported"});
    writeBytes("b.png", "GIF89a\x01\x00\x01\x00");
    expectInputError([&] { readImage(path("b.png")); }, {"b.png: GIF images are not supported"});
    writeBytes("c.jpg", "8BPS\x00\x01");
    expectInputError([&] { readImage(path("c.jpg")); }, {"c.jpg: PSD images are not supported"});
}

// stb would zero-fill the missing rows of a BMP whose height field is damaged: gigabytes
// from a few hundred bytes. The size check stops it before decoding.
TEST_F(ImageErrors, DamagedBmpHeightIsRejectedBeforeDecoding) {
    unsigned char px[16 * 12 * 3] = {};
    ASSERT_TRUE(stbi_write_bmp(path("h.bmp").c_str(), 16, 12, 3, px));
    std::string bytes = readBytes("h.bmp");
    const int32_t height = 10000000;
    ASSERT_GT(bytes.size(), 26u);
    std::memcpy(&bytes[22], &height, 4);  // BITMAPINFOHEADER biHeight, little endian
    writeBytes("h.bmp", bytes);
    expectInputError([&] { readImage(path("h.bmp")); }, {"h.bmp", "16x10000000", "implausible"});
}

TEST_F(ImageErrors, TruncatedFiles) {
    Image img = testPattern(32, 32);
    writeImage(path("t.png"), img);
    writeImage(path("t.exr"), img);
    writeImage(path("t.pfm"), img);
    unsigned char px[32 * 32 * 3];
    for (size_t i = 0; i < sizeof px; ++i) px[i] = (unsigned char)(i * 37);
    ASSERT_TRUE(stbi_write_jpg(path("t.jpg").c_str(), 32, 32, 3, px, 90));
    ASSERT_TRUE(stbi_write_tga(path("t.tga").c_str(), 32, 32, 3, px));
    ASSERT_TRUE(stbi_write_bmp(path("t.bmp").c_str(), 32, 32, 3, px));
    std::vector<float> hdr(32 * 32 * 3);
    for (size_t i = 0; i < hdr.size(); ++i) hdr[i] = float(i % 97) / 7.0f;
    ASSERT_TRUE(stbi_write_hdr(path("t.hdr").c_str(), 32, 32, 3, hdr.data()));  // run-length encoded

    for (std::string name : {"t.png", "t.exr", "t.pfm", "t.jpg", "t.tga", "t.bmp", "t.hdr"}) {
        std::string bytes = readBytes(name);
        for (size_t keep : {size_t(0), size_t(3), size_t(10), bytes.size() / 3, bytes.size() / 2, bytes.size() - 20,
                            bytes.size() - 1}) {
            const std::string cut = "cut" + std::to_string(keep) + "-" + name;
            writeBytes(cut, bytes.substr(0, keep));
            expectInputError([&] { readImage(path(cut)); }, {cut});
        }
    }
    // Every cut inside a run-length encoded HDR: stb's reader would loop forever here.
    std::string bytes = readBytes("t.hdr");
    for (size_t keep = bytes.size() - 300; keep < bytes.size(); ++keep) {
        writeBytes("cut.hdr", bytes.substr(0, keep));
        expectInputError([&] { readImage(path("cut.hdr")); }, {"cut.hdr: truncated HDR data"});
    }
}

TEST_F(ImageErrors, BadHdrHeaders) {
    const std::string pixels(16, char(0x80));
    writeBytes("xyze.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 2\n" + pixels);
    expectInputError([&] { readImage(path("xyze.hdr")); }, {"xyze.hdr", "32-bit_rle_xyze"});
    writeBytes("flip.hdr", "#?RADIANCE\n\n+Y 2 +X 2\n" + pixels);
    expectInputError([&] { readImage(path("flip.hdr")); }, {"flip.hdr", "+Y 2 +X 2"});
    writeBytes("junk.hdr", "#?RADIANCE\n\n-Y 2 +X 2 junk\n" + pixels);
    expectInputError([&] { readImage(path("junk.hdr")); }, {"junk.hdr", "resolution"});
    writeBytes("huge.hdr", "#?RADIANCE\n\n-Y 99999999999 +X 99999999999\n" + pixels);
    expectInputError([&] { readImage(path("huge.hdr")); }, {"huge.hdr"});
    writeBytes("neg.hdr", "#?RADIANCE\n\n-Y -2 +X 2\n" + pixels);
    expectInputError([&] { readImage(path("neg.hdr")); }, {"neg.hdr", "out of range"});
    writeBytes("noheader.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n");
    expectInputError([&] { readImage(path("noheader.hdr")); }, {"noheader.hdr", "truncated HDR header"});
    writeBytes("other.hdr", "#?SOMETHING\n\n-Y 1 +X 1\n" + pixels);
    expectInputError([&] { readImage(path("other.hdr")); }, {"other.hdr", "not a Radiance HDR file"});
}

// Random byte damage to valid files of every format: reading may succeed or throw
// InputError, but must not crash or throw anything else.
TEST_F(ImageErrors, CorruptedFilesNeverCrash) {
    Image img = testPattern(16, 12);
    writeImage(path("f.png"), img);
    writeImage(path("f.exr"), img);
    writeImage(path("f.pfm"), img);
    unsigned char px[16 * 12 * 4];
    for (size_t i = 0; i < sizeof px; ++i) px[i] = (unsigned char)(i * 29 + 7);
    ASSERT_TRUE(stbi_write_jpg(path("f.jpg").c_str(), 16, 12, 3, px, 90));
    ASSERT_TRUE(stbi_write_tga(path("f.tga").c_str(), 16, 12, 4, px));
    ASSERT_TRUE(stbi_write_bmp(path("f.bmp").c_str(), 16, 12, 3, px));
    std::vector<float> hdr(16 * 12 * 3);
    for (size_t i = 0; i < hdr.size(); ++i) hdr[i] = float(i % 13) * 0.3f;
    ASSERT_TRUE(stbi_write_hdr(path("f.hdr").c_str(), 16, 12, 3, hdr.data()));
    writeBytes("f16.png", png16(4, 3, 6, std::vector<uint16_t>(4 * 3 * 4, 40000)));

    std::mt19937 rng(1234);
    for (const char* name : {"f.png", "f.exr", "f.pfm", "f.jpg", "f.tga", "f.bmp", "f.hdr", "f16.png"}) {
        const std::string original = readBytes(name);
        int ok = 0, rejected = 0;
        for (int trial = 0; trial < 150; ++trial) {
            std::string bytes = original;
            int edits = 1 + int(rng() % 8);
            for (int e = 0; e < edits; ++e) {
                // Mostly in the header, where sizes and offsets live.
                size_t limit = rng() % 2 ? std::min<size_t>(bytes.size(), 64) : bytes.size();
                size_t at = rng() % limit;
                bytes[at] = rng() % 3 == 0 ? char(0xff) : char(rng());
            }
            writeBytes("fuzz" + fs::path(name).extension().string(), bytes);
            try {
                Image back = readImage(path("fuzz" + fs::path(name).extension().string()));
                EXPECT_EQ(back.rgb.size(), size_t(back.width) * back.height * 3);
                ++ok;
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("fuzz"), std::string::npos) << e.what();
                ++rejected;
            }
        }
        EXPECT_EQ(ok + rejected, 150) << name;
    }
}
