#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "image/image_test_util.h"
#include "image/png_builder.h"
#include "shared_data.h"

using namespace ps;
using namespace ps::test;
namespace fs = std::filesystem;

namespace {

using ImageRead = TempDirTest;

float srgb8(int v) { return srgbToLinear(v / 255.0f); }

// Little- or big-endian float bytes for hand-made PFM files.
std::string floatBytes(std::initializer_list<float> values, bool little) {
    std::string out;
    for (float v : values) {
        unsigned char b[4];
        std::memcpy(b, &v, 4);
        if (!little) std::reverse(b, b + 4);  // the host is little endian
        out.append(reinterpret_cast<char*>(b), 4);
    }
    return out;
}

}  // namespace

// TGA, JPEG and BMP are sRGB-decoded whatever encoding is asked for (PBRT-CONVENTIONS §6).
TEST_F(ImageRead, TgaBmpJpegAreAlwaysSrgbDecoded) {
    const unsigned char px[2 * 2 * 3] = {128, 128, 128, 255, 0, 10, 0, 0, 0, 64, 200, 30};
    ASSERT_TRUE(stbi_write_tga(path("a.tga").c_str(), 2, 2, 3, px));
    ASSERT_TRUE(stbi_write_bmp(path("a.bmp").c_str(), 2, 2, 3, px));
    for (const char* name : {"a.tga", "a.bmp"})
        for (ColorEncoding enc : {ColorEncoding::SRGB, ColorEncoding::Linear}) {
            Image img = readImage(path(name), enc);
            ASSERT_EQ(img.width, 2);
            ASSERT_EQ(img.height, 2);
            for (int i = 0; i < 12; ++i) EXPECT_EQ(img.rgb[i], srgb8(px[i])) << name << " " << i;
            EXPECT_TRUE(img.alpha.empty());
        }

    unsigned char grey[16 * 16 * 3];
    std::fill(std::begin(grey), std::end(grey), 128);
    ASSERT_TRUE(stbi_write_jpg(path("a.jpg").c_str(), 16, 16, 3, grey, 95));
    Image jpg = readImage(path("a.jpg"), ColorEncoding::Linear);
    ASSERT_EQ(jpg.width, 16);
    for (float v : jpg.rgb) EXPECT_NEAR(v, srgb8(128), srgb8(129) - srgb8(128)) << "lossy, so one step";
}

TEST_F(ImageRead, TgaAlphaAndGreyscale) {
    const unsigned char rgba[4] = {255, 128, 0, 51};
    ASSERT_TRUE(stbi_write_tga(path("rgba.tga").c_str(), 1, 1, 4, rgba));
    Image img = readImage(path("rgba.tga"));
    EXPECT_EQ(img.get(0, 0).r, 1.0f);
    EXPECT_EQ(img.get(0, 0).g, srgb8(128));
    ASSERT_EQ(img.alpha.size(), 1u);
    EXPECT_EQ(img.alpha[0], 51 / 255.0f);  // alpha is linear

    const unsigned char grey[3] = {0, 100, 255};
    ASSERT_TRUE(stbi_write_tga(path("grey.tga").c_str(), 3, 1, 1, grey));
    Image g = readImage(path("grey.tga"));
    for (int x = 0; x < 3; ++x) {
        Spectrum s = g.get(x, 0);
        EXPECT_EQ(s.r, srgb8(grey[x]));
        EXPECT_EQ(s.g, s.r);
        EXPECT_EQ(s.b, s.r);
    }
}

TEST_F(ImageRead, Png8BitHonoursEncodingButAlphaStaysLinear) {
    const unsigned char greyAlpha[2 * 2] = {128, 255, 64, 0};  // two grey+alpha pixels
    ASSERT_TRUE(stbi_write_png(path("ga.png").c_str(), 2, 1, 2, greyAlpha, 4));
    Image s = readImage(path("ga.png"));
    Image l = readImage(path("ga.png"), ColorEncoding::Linear);
    EXPECT_EQ(s.get(0, 0).b, srgb8(128));
    EXPECT_EQ(l.get(0, 0).b, 128 / 255.0f);
    EXPECT_EQ(s.get(1, 0).r, srgb8(64));
    EXPECT_EQ(l.get(1, 0).g, 64 / 255.0f);
    for (const Image* img : {&s, &l}) {
        ASSERT_EQ(img->alpha.size(), 2u);
        EXPECT_EQ(img->alpha[0], 1.0f);
        EXPECT_EQ(img->alpha[1], 0.0f);
    }
}

TEST_F(ImageRead, Png16Bit) {
    writeBytes("rgb16.png", png16(2, 1, 2, {0, 1000, 65535, 32768, 12345, 300}));
    Image lin = readImage(path("rgb16.png"), ColorEncoding::Linear);
    ASSERT_EQ(lin.width, 2);
    EXPECT_EQ(lin.get(0, 0).g, 1000 / 65535.0f);
    EXPECT_EQ(lin.get(0, 0).b, 1.0f);
    EXPECT_EQ(lin.get(1, 0).r, 32768 / 65535.0f);
    Image dec = readImage(path("rgb16.png"));
    EXPECT_EQ(dec.get(1, 0).g, srgbToLinear(12345 / 65535.0f));

    writeBytes("ga16.png", png16(1, 2, 4, {40000, 65535, 20000, 16384}));
    Image ga = readImage(path("ga16.png"));
    ASSERT_EQ(ga.height, 2);
    EXPECT_EQ(ga.get(0, 1).r, srgbToLinear(20000 / 65535.0f));
    EXPECT_EQ(ga.get(0, 1).b, ga.get(0, 1).r);
    ASSERT_EQ(ga.alpha.size(), 2u);
    EXPECT_EQ(ga.alpha[0], 1.0f);
    EXPECT_EQ(ga.alpha[1], 16384 / 65535.0f);
}

TEST_F(ImageRead, RadianceHdrIsLinear) {
    const float px[2 * 3] = {0.5f, 1.0f, 4.0f, 100.0f, 0.25f, 0.0f};
    ASSERT_TRUE(stbi_write_hdr(path("a.hdr").c_str(), 2, 1, 3, px));  // flat: too narrow for RLE
    for (ColorEncoding enc : {ColorEncoding::SRGB, ColorEncoding::Linear}) {
        Image img = readImage(path("a.hdr"), enc);
        ASSERT_EQ(img.width, 2);
        // RGBE: 8 mantissa bits shared by the pixel's three channels.
        for (int i = 0; i < 6; ++i) EXPECT_NEAR(img.rgb[i], px[i], std::max(px[i / 3 * 3], px[i / 3 * 3 + 1]) / 128) << i;
        EXPECT_TRUE(img.alpha.empty());
    }
}

// Our RGBE reader must give exactly what stb_image (which pbrt-v4 uses) gives.
TEST_F(ImageRead, RadianceHdrMatchesStbBitForBit) {
    const int w = 40, h = 3;
    std::vector<float> px(w * h * 3);
    for (size_t i = 0; i < px.size(); ++i) px[i] = i % 5 == 0 ? 0.0f : std::pow(1.7f, float(i % 23) - 11.0f) * (1 + i % 3);
    for (int x = 10; x < 30; ++x) px[3 * x] = px[3 * x + 1] = px[3 * x + 2] = 0.75f;  // a run
    ASSERT_TRUE(stbi_write_hdr(path("rle.hdr").c_str(), w, h, 3, px.data()));
    std::string bytes = readBytes("rle.hdr");
    int sw = 0, sh = 0, sc = 0;
    std::unique_ptr<float, void (*)(void*)> ref(
        stbi_loadf_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &sw, &sh, &sc, 3),
        stbi_image_free);
    ASSERT_TRUE(ref);
    Image img = readImage(path("rle.hdr"));
    ASSERT_EQ(img.width, w);
    ASSERT_EQ(img.height, h);
    EXPECT_EQ(std::memcmp(img.rgb.data(), ref.get(), img.rgb.size() * sizeof(float)), 0);
    EXPECT_FLOAT_EQ(img.get(20, 0).g, 0.75f);

    // The other magic line, and no FORMAT line (rgbe is the default).
    std::string pixels = "\x80\x40\x20\x81";  // (128, 64, 32) * 2^(129-136)
    writeBytes("rgbe.hdr", "#?RGBE\n# comment\n\n-Y 1 +X 1\n" + pixels);
    Image one = readImage(path("rgbe.hdr"));
    EXPECT_EQ(one.get(0, 0).r, 1.0f);
    EXPECT_EQ(one.get(0, 0).g, 0.5f);
    EXPECT_EQ(one.get(0, 0).b, 0.25f);
}

// stb "decodes" a TGA cut short, with unset memory for the missing rows: that must be an
// error, while complete files (however small) read cleanly.
TEST_F(ImageRead, TruncationIsDetectedBehindStb) {
    unsigned char px[8 * 8 * 3];
    for (size_t i = 0; i < sizeof px; ++i) px[i] = (unsigned char)(i * 11);
    stbi_write_tga_with_rle = 0;
    ASSERT_TRUE(stbi_write_tga(path("full.tga").c_str(), 8, 8, 3, px));
    stbi_write_tga_with_rle = 1;
    ASSERT_TRUE(stbi_write_tga(path("rle.tga").c_str(), 8, 8, 3, px));
    ASSERT_TRUE(stbi_write_bmp(path("full.bmp").c_str(), 8, 8, 3, px));
    const unsigned char one[3] = {1, 2, 3};
    ASSERT_TRUE(stbi_write_tga(path("one.tga").c_str(), 1, 1, 3, one));
    ASSERT_TRUE(stbi_write_png(path("one.png").c_str(), 1, 1, 3, one, 3));
    ASSERT_TRUE(stbi_write_jpg(path("one.jpg").c_str(), 1, 1, 3, one, 90));
    ASSERT_TRUE(stbi_write_bmp(path("one.bmp").c_str(), 1, 1, 3, one));
    for (const char* name : {"full.tga", "rle.tga", "full.bmp", "one.tga", "one.png", "one.jpg", "one.bmp"})
        EXPECT_NO_THROW(readImage(path(name))) << name;

    for (std::string name : {"full.tga", "rle.tga", "full.bmp"}) {
        std::string bytes = readBytes(name);
        writeBytes("cut-" + name, bytes.substr(0, bytes.size() - 30));
        expectInputError([&] { readImage(path("cut-" + name)); }, {"cut-" + name + ": truncated image data"});
    }
}

TEST_F(ImageRead, PfmColourLittleEndianRowsFlipped) {
    // File rows: bottom row first.
    writeBytes("c.pfm", "PF\n2 2\n-1.0\n" + floatBytes({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, true));
    Image img = readImage(path("c.pfm"));
    ASSERT_EQ(img.width, 2);
    ASSERT_EQ(img.height, 2);
    EXPECT_EQ(img.get(0, 1).r, 1.0f);  // bottom-left
    EXPECT_EQ(img.get(1, 1).b, 6.0f);
    EXPECT_EQ(img.get(0, 0).r, 7.0f);  // top-left
    EXPECT_EQ(img.get(1, 0).b, 12.0f);
    EXPECT_TRUE(img.alpha.empty());
}

TEST_F(ImageRead, PfmGreyscaleBigEndian) {
    writeBytes("g.pfm", "Pf\n3 1\n1\n" + floatBytes({0.25f, 2.0f, -1e-3f}, false));
    Image img = readImage(path("g.pfm"));
    ASSERT_EQ(img.width, 3);
    ASSERT_EQ(img.height, 1);
    const float expected[3] = {0.25f, 2.0f, -1e-3f};
    for (int x = 0; x < 3; ++x) {
        EXPECT_EQ(img.get(x, 0).r, expected[x]);
        EXPECT_EQ(img.get(x, 0).g, expected[x]);
        EXPECT_EQ(img.get(x, 0).b, expected[x]);
    }
}

// pbrt-v4 multiplies by |scale|; almost every file uses 1.
TEST_F(ImageRead, PfmScaleMagnitudeAppliesAndFormatIsSniffed) {
    writeBytes("s.pfm", "Pf 1 1 -2.5 " + floatBytes({4.0f}, true));
    EXPECT_EQ(readImage(path("s.pfm")).get(0, 0).g, 10.0f);
    // Content decides, not the name.
    writeBytes("really-a-pfm.png", "Pf\n1 1\n-1\n" + floatBytes({0.75f}, true));
    EXPECT_EQ(readImage(path("really-a-pfm.png")).get(0, 0).r, 0.75f);
}

TEST_F(ImageRead, ExrHalfRgbaWithAlpha) {
    {
        Imf::Rgba px[2] = {Imf::Rgba(0.5f, 2.0f, 1024.0f, 0.25f), Imf::Rgba(-1.0f, 0.0f, 0.125f, 1.0f)};
        Imf::RgbaOutputFile out(path("h.exr").c_str(), 2, 1, Imf::WRITE_RGBA);
        out.setFrameBuffer(px, 1, 2);
        out.writePixels(1);
    }
    Image img = readImage(path("h.exr"), ColorEncoding::SRGB);  // EXR is always linear
    ASSERT_EQ(img.width, 2);
    EXPECT_EQ(img.get(0, 0).r, 0.5f);
    EXPECT_EQ(img.get(0, 0).b, 1024.0f);
    EXPECT_EQ(img.get(1, 0).r, -1.0f);
    ASSERT_EQ(img.alpha.size(), 2u);
    EXPECT_EQ(img.alpha[0], 0.25f);
    EXPECT_EQ(img.alpha[1], 1.0f);
}

namespace {

// A float EXR with the given channels, each filled by value(channelIndex, x, y).
template <typename F>
void writeExr(const std::string& file, const Imath::Box2i& display, const Imath::Box2i& data,
              std::vector<std::string> channels, F value) {
    Imf::Header header(display, data);
    int w = data.max.x - data.min.x + 1, h = data.max.y - data.min.y + 1;
    std::vector<std::vector<float>> planes(channels.size(), std::vector<float>(size_t(w) * h));
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < channels.size(); ++c) {
        header.channels().insert(channels[c], Imf::Channel(Imf::FLOAT));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) planes[c][size_t(y) * w + x] = value(int(c), x, y);
        fb.insert(channels[c], Imf::Slice::Make(Imf::FLOAT, planes[c].data(), data));
    }
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(h);
}

}  // namespace

TEST_F(ImageRead, ExrGreyscaleAndDataWindow) {
    Imath::Box2i display({0, 0}, {9, 9}), data({2, 3}, {5, 4});
    writeExr(path("y.exr"), display, data, {"Y"}, [](int, int x, int y) { return float(x + 10 * y); });
    Image img = readImage(path("y.exr"));
    ASSERT_EQ(img.width, 4);  // the data window is the image
    ASSERT_EQ(img.height, 2);
    EXPECT_EQ(img.get(3, 1).r, 13.0f);
    EXPECT_EQ(img.get(3, 1).g, 13.0f);
    EXPECT_EQ(img.get(3, 1).b, 13.0f);
    EXPECT_TRUE(img.alpha.empty());

    writeExr(path("z.exr"), data, data, {"Z"}, [](int, int, int) { return 1.0f; });
    expectInputError([&] { readImage(path("z.exr")); }, {"z.exr", "Z"});
}

// The shared pbrt-v4 references come as EXR and PFM holding the same floats.
TEST_F(ImageRead, ReferenceExrAndPfmAgree) {
    fs::path refs = fs::path(PATHSPACE_SHARED_DIR) / "refs";
    std::string exr = (refs / "cornell-box-path-4096spp.exr").string();
    std::string pfm = (refs / "cornell-box-path-4096spp.pfm").string();
    REQUIRE_SHARED_DATA(exr, pfm);
    Image a = readImage(exr), b = readImage(pfm);
    ASSERT_EQ(a.width, 256);
    ASSERT_EQ(a.height, 256);
    ASSERT_EQ(b.width, 256);
    ASSERT_EQ(b.height, 256);
    EXPECT_EQ(a.rgb, b.rgb);
    double mean[3] = {0, 0, 0};
    for (size_t i = 0; i < b.rgb.size(); ++i) mean[i % 3] += b.rgb[i];
    const double expected[3] = {0.19501, 0.12677, 0.034699};  // refs/README.md
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c] / (256.0 * 256.0), expected[c], 1e-4 * expected[c]) << c;
}
