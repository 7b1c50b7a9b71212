// Shared by the image tests: a fresh temporary directory per test and an InputError check.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "image/image.h"
#include "util/error.h"

namespace ps::test {

class TempDirTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = std::filesystem::temp_directory_path() /
              ("pathspace-image-" + std::to_string(getpid()) + "-" + info->test_suite_name() + "-" + info->name());
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    void writeBytes(const std::string& name, const std::string& bytes) const {
        std::ofstream(path(name), std::ios::binary) << bytes;
    }
    std::string readBytes(const std::string& name) const {
        std::ifstream in(path(name), std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    std::filesystem::path dir;
};

// Runs f, which must throw InputError whose message contains every needle.
template <typename F>
void expectInputError(F&& f, std::initializer_list<std::string> needles) {
    try {
        f();
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        for (const std::string& n : needles)
            EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << "\"" << n << "\" not in: " << e.what();
    }
}

// Distinct, non-trivial values: negative, tiny, large, fractional.
inline Image testPattern(int w, int h) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.set(x, y, Spectrum(x / float(w) + 1e-30f * y, y / float(h) - 0.125f * x, 0.1f + 1234.5f * x * y));
    return img;
}

}  // namespace ps::test
