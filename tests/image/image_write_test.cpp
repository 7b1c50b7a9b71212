#include <signal.h>
#include <sys/resource.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "image/image_test_util.h"

using namespace ps;
using namespace ps::test;
namespace fs = std::filesystem;

namespace {

class ImageWrite : public TempDirTest {
protected:
    // Nothing but the expected files: no temporaries left behind.
    void expectNoTemporaries() const {
        for (auto& e : fs::recursive_directory_iterator(dir))
            EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
    }
};

Image withSpecialValues() {
    Image img = testPattern(7, 5);
    img.rgb[0] = 1e-40f;  // denormal
    img.rgb[1] = -0.0f;
    img.rgb[2] = std::numeric_limits<float>::max();
    img.rgb[3] = 0.1f;
    return img;
}

}  // namespace

TEST_F(ImageWrite, ExrAndPfmRoundTripBitExact) {
    Image img = withSpecialValues();
    for (const char* name : {"a.exr", "a.pfm", "UPPER.EXR", "Mixed.Pfm"}) {
        writeImage(path(name), img);
        Image back = readImage(path(name));
        ASSERT_EQ(back.width, 7) << name;
        ASSERT_EQ(back.height, 5) << name;
        ASSERT_EQ(back.rgb.size(), img.rgb.size());
        EXPECT_EQ(std::memcmp(back.rgb.data(), img.rgb.data(), img.rgb.size() * sizeof(float)), 0) << name;
        EXPECT_TRUE(back.alpha.empty()) << name;
    }
    expectNoTemporaries();
}

// Within one 8-bit step of the sRGB encoding (half a step of rounding, plus float slack).
TEST_F(ImageWrite, PngRoundTripWithinOneStep) {
    Image img(16, 9);
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 16; ++x) img.set(x, y, Spectrum(x / 15.0f, y / 8.0f, (x * 7 + y * 3) % 11 / 10.0f));
    writeImage(path("a.png"), img);
    Image back = readImage(path("a.png"));
    ASSERT_EQ(back.width, 16);
    ASSERT_EQ(back.height, 9);
    for (size_t i = 0; i < img.rgb.size(); ++i)
        EXPECT_NEAR(linearToSrgb(back.rgb[i]), linearToSrgb(img.rgb[i]), 1.0f / 255.0f) << i;
    // The stored bytes are the sRGB encoding: read raw (Linear), 1.0 stays 1.0 and 0.5 is 188/255.
    Image raw = readImage(path("a.png"), ColorEncoding::Linear);
    EXPECT_EQ(raw.get(15, 0).r, 1.0f);
    img.set(0, 0, Spectrum(0.5f));
    writeImage(path("b.png"), img);
    EXPECT_EQ(readImage(path("b.png"), ColorEncoding::Linear).get(0, 0).g, 188 / 255.0f);
}

TEST_F(ImageWrite, PngClampsToUnitRange) {
    Image img(3, 1);
    img.set(0, 0, Spectrum(-2.0f));
    img.set(1, 0, Spectrum(7.0f));
    img.set(2, 0, Spectrum(0.0f, 1.0f, 1e30f));
    writeImage(path("c.png"), img);
    Image raw = readImage(path("c.png"), ColorEncoding::Linear);
    EXPECT_EQ(raw.get(0, 0).r, 0.0f);
    EXPECT_EQ(raw.get(1, 0).r, 1.0f);
    EXPECT_EQ(raw.get(2, 0).b, 1.0f);
}

TEST_F(ImageWrite, PfmLayoutIsLittleEndianBottomUp) {
    Image img(2, 2);
    img.set(0, 0, Spectrum(1.0f));  // top-left
    img.set(0, 1, Spectrum(2.0f));  // bottom-left: first in the file
    writeImage(path("l.pfm"), img);
    std::string bytes = readBytes("l.pfm");
    const std::string header = "PF\n2 2\n-1\n";
    ASSERT_EQ(bytes.size(), header.size() + 2 * 2 * 3 * 4);
    EXPECT_EQ(bytes.substr(0, header.size()), header);
    const unsigned char two[4] = {0x00, 0x00, 0x00, 0x40};  // 2.0f, little endian
    EXPECT_EQ(std::memcmp(bytes.data() + header.size(), two, 4), 0);
}

TEST_F(ImageWrite, NonFiniteValuesNeverReachTheFile) {
    const float inf = std::numeric_limits<float>::infinity(), big = std::numeric_limits<float>::max();
    Image img(2, 1);
    img.set(0, 0, Spectrum(std::numeric_limits<float>::quiet_NaN(), inf, -inf));
    img.set(1, 0, Spectrum(-std::numeric_limits<float>::signaling_NaN(), 0.5f, 1.0f));
    for (const char* name : {"n.exr", "n.pfm"}) {
        writeImage(path(name), img);
        Image back = readImage(path(name));
        EXPECT_EQ(back.get(0, 0).r, 0.0f) << name;
        EXPECT_EQ(back.get(0, 0).g, big) << name;
        EXPECT_EQ(back.get(0, 0).b, -big) << name;
        EXPECT_EQ(back.get(1, 0).r, 0.0f) << name;
        EXPECT_EQ(back.get(1, 0).g, 0.5f) << name;
    }
    writeImage(path("n.png"), img);
    Image png = readImage(path("n.png"), ColorEncoding::Linear);
    EXPECT_EQ(png.get(0, 0).r, 0.0f);
    EXPECT_EQ(png.get(0, 0).g, 1.0f);
    EXPECT_EQ(png.get(0, 0).b, 0.0f);
}

TEST_F(ImageWrite, OverwritesAnExistingFile) {
    writeImage(path("o.pfm"), testPattern(3, 3));
    Image second = testPattern(4, 2);
    writeImage(path("o.pfm"), second);
    EXPECT_EQ(readImage(path("o.pfm")).rgb, second.rgb);
    expectNoTemporaries();
}

TEST_F(ImageWrite, WritableExtensions) {
    EXPECT_TRUE(isWritableImageExtension("a.exr"));
    EXPECT_TRUE(isWritableImageExtension("dir.d/a.PFM"));
    EXPECT_TRUE(isWritableImageExtension("a.Png"));
    EXPECT_FALSE(isWritableImageExtension("a.tga"));
    EXPECT_FALSE(isWritableImageExtension("a.jpg"));
    EXPECT_FALSE(isWritableImageExtension("exr"));
    EXPECT_FALSE(isWritableImageExtension("a.exr/b"));
    EXPECT_FALSE(isWritableImageExtension(""));
}

TEST_F(ImageWrite, UnknownExtensionListsTheSupportedOnes) {
    Image img = testPattern(2, 2);
    expectInputError([&] { writeImage(path("x.tga"), img); }, {"x.tga", ".exr", ".pfm", ".png"});
    expectInputError([&] { writeImage(path("noext"), img); }, {"noext", "unsupported"});
    EXPECT_FALSE(fs::exists(path("x.tga")));
    expectNoTemporaries();
}

TEST_F(ImageWrite, UnwritableLocationNamesPathAndReason) {
    Image img = testPattern(2, 2);
    expectInputError([&] { writeImage("/nonexistent-dir/x.exr", img); },
                     {"/nonexistent-dir/x.exr", "No such file or directory"});
    expectInputError([&] { writeImage("/nonexistent-dir/x.png", img); }, {"/nonexistent-dir/x.png"});
    // A directory where the file should go: the rename fails, nothing is left behind.
    fs::create_directories(dir / "taken.pfm" / "inside");
    expectInputError([&] { writeImage(path("taken.pfm"), img); }, {"taken.pfm", "directory"});
    EXPECT_TRUE(fs::is_directory(dir / "taken.pfm" / "inside"));
    expectNoTemporaries();
}

TEST_F(ImageWrite, MalformedImageIsRejected) {
    Image empty;
    expectInputError([&] { writeImage(path("e.exr"), empty); }, {"e.exr", "invalid image"});
    Image inconsistent = testPattern(4, 4);
    inconsistent.rgb.resize(5);
    expectInputError([&] { writeImage(path("i.png"), inconsistent); }, {"i.png", "invalid image"});
    EXPECT_TRUE(fs::is_empty(dir));
}

// A write that fails half-way (here: the file size limit, as on a full disk) must leave
// the previous file intact and remove its temporary.
TEST_F(ImageWrite, FailedWriteKeepsTheExistingFile) {
    Image old = testPattern(2, 2);
    for (const char* name : {"keep.pfm", "keep.exr", "keep.png"}) {
        writeImage(path(name), old);
        std::string before = readBytes(name);

        rlimit saved;
        ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
        auto oldHandler = signal(SIGXFSZ, SIG_IGN);  // get EFBIG instead of a signal
        rlimit small = saved;
        small.rlim_cur = 64;
        ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
        Image big = testPattern(64, 64);
        for (float& v : big.rgb) v = std::sin(v * 12.9898f) * 43758.5453f;  // incompressible for EXR/PNG
        try {
            writeImage(path(name), big);
            ADD_FAILURE() << name << ": write past the file size limit succeeded";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(std::strerror(EFBIG)), std::string::npos) << e.what();
        }
        setrlimit(RLIMIT_FSIZE, &saved);
        signal(SIGXFSZ, oldHandler);

        EXPECT_EQ(readBytes(name), before) << name;
        EXPECT_EQ(readImage(path(name)).width, 2) << name;
    }
    expectNoTemporaries();
}
