#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "image/image.h"
#include "util/error.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

class ImageIO : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("pathspace-img-" + std::to_string(getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string path(const std::string& n) const { return (dir / n).string(); }
    static Image gradient(int w, int h) {
        Image img(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) img.set(x, y, Spectrum(x / float(w), y / float(h), 0.25f + 3.5f * x * y));
        return img;
    }
    fs::path dir;
};

template <typename F>
void expectInputErrorMentioning(F&& f, const std::string& needle) {
    try {
        f();
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
}

}  // namespace

TEST_F(ImageIO, ExrAndPfmRoundTripExactly) {
    Image img = gradient(7, 5);
    for (const char* name : {"a.exr", "a.pfm"}) {
        writeImage(path(name), img);
        Image back = readImage(path(name));
        ASSERT_EQ(back.width, 7);
        ASSERT_EQ(back.height, 5);
        EXPECT_EQ(back.rgb, img.rgb) << name;
    }
}

TEST_F(ImageIO, PngRoundTripWithinQuantisation) {
    Image img(4, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) img.set(x, y, Spectrum(x / 3.0f, y / 2.0f, 0.5f));
    writeImage(path("a.png"), img);
    Image back = readImage(path("a.png"));
    for (size_t i = 0; i < img.rgb.size(); ++i) {
        // One 8-bit step of the sRGB curve is at most ~0.013 in linear terms near 1.
        EXPECT_NEAR(back.rgb[i], img.rgb[i], 0.014f);
    }
    Image linear = readImage(path("a.png"), ColorEncoding::Linear);
    EXPECT_NEAR(linear.get(3, 0).r, 1.0f, 1e-6f);
    EXPECT_NEAR(linear.get(0, 0).b, linearToSrgb(0.5f), 0.005f);
}

TEST_F(ImageIO, SrgbCurve) {
    EXPECT_FLOAT_EQ(srgbToLinear(0), 0);
    EXPECT_NEAR(srgbToLinear(1), 1, 1e-6);
    EXPECT_NEAR(srgbToLinear(0.5f), 0.21404f, 1e-4);
    float prev = -1;
    for (int i = 0; i <= 1000; ++i) {
        float v = srgbToLinear(i / 1000.0f);
        EXPECT_GT(v, prev);
        prev = v;
        EXPECT_NEAR(linearToSrgb(v), i / 1000.0f, 1e-5);
    }
}

// TGA and JPEG are always sRGB-decoded, whatever encoding is asked for.
TEST_F(ImageIO, TgaAndJpegAreSrgbDecoded) {
    unsigned char px[2 * 2 * 3] = {128, 128, 128, 255, 255, 255, 0, 0, 0, 64, 64, 64};
    ASSERT_TRUE(stbi_write_tga(path("a.tga").c_str(), 2, 2, 3, px));
    Image tga = readImage(path("a.tga"), ColorEncoding::Linear);
    EXPECT_NEAR(tga.get(0, 0).r, srgbToLinear(128 / 255.0f), 1e-6f);
    EXPECT_NEAR(tga.get(1, 0).g, 1.0f, 1e-6f);
    unsigned char grey[8 * 8 * 3];
    std::fill(grey, grey + sizeof grey, 128);
    ASSERT_TRUE(stbi_write_jpg(path("a.jpg").c_str(), 8, 8, 3, grey, 95));
    Image jpg = readImage(path("a.jpg"));
    EXPECT_NEAR(jpg.get(4, 4).g, srgbToLinear(128 / 255.0f), 0.01f);
}

TEST_F(ImageIO, GreyscalePfmBigEndian) {
    std::ofstream f(path("g.pfm"), std::ios::binary);
    f << "Pf\n2 1\n1.0\n";
    float vals[2] = {0.25f, 2.0f};
    for (float v : vals) {
        uint32_t u;
        std::memcpy(&u, &v, 4);
        u = __builtin_bswap32(u);
        f.write(reinterpret_cast<const char*>(&u), 4);
    }
    f.close();
    Image img = readImage(path("g.pfm"));
    EXPECT_FLOAT_EQ(img.get(0, 0).g, 0.25f);
    EXPECT_FLOAT_EQ(img.get(1, 0).b, 2.0f);
}

TEST_F(ImageIO, BadInputsThrowInputErrorNamingTheFile) {
    expectInputErrorMentioning([&] { readImage(path("missing.png")); }, "missing.png");
    std::ofstream(path("text.png")) << "this is not an image";
    expectInputErrorMentioning([&] { readImage(path("text.png")); }, "text.png");
    std::ofstream(path("short.pfm"), std::ios::binary) << "PF\n100 100\n-1\nabc";
    expectInputErrorMentioning([&] { readImage(path("short.pfm")); }, "short.pfm");
    std::ofstream(path("huge.pfm"), std::ios::binary) << "PF\n1000000 1000000\n-1\n";
    expectInputErrorMentioning([&] { readImage(path("huge.pfm")); }, "huge.pfm");
    std::ofstream(path("bad.exr")) << "nope";
    expectInputErrorMentioning([&] { readImage(path("bad.exr")); }, "bad.exr");
    Image img = gradient(2, 2);
    expectInputErrorMentioning([&] { writeImage(path("x.tga"), img); }, "x.tga");
    expectInputErrorMentioning([&] { writeImage("/nonexistent-dir/x.exr", img); }, "/nonexistent-dir/x.exr");
}

TEST_F(ImageIO, FailedWriteKeepsTheOldFileAndNonFiniteIsNeverWritten) {
    Image img = gradient(3, 3);
    writeImage(path("keep.pfm"), img);
    Image bad = gradient(3, 3);
    bad.rgb[0] = std::numeric_limits<float>::quiet_NaN();
    bad.rgb[1] = std::numeric_limits<float>::infinity();
    writeImage(path("nan.exr"), bad);
    Image back = readImage(path("nan.exr"));
    EXPECT_EQ(back.rgb[0], 0.0f);
    EXPECT_TRUE(std::isfinite(back.rgb[1]));
    // A directory in the way makes the rename fail; the earlier file stays intact.
    fs::create_directories(dir / "sub" / "keep.pfm" / "x");
    writeImage(path("sub2.pfm"), img);
    EXPECT_THROW(writeImage((dir / "sub" / "keep.pfm").string(), img), InputError);
    EXPECT_EQ(readImage(path("keep.pfm")).rgb, img.rgb);
    for (auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos);
}
