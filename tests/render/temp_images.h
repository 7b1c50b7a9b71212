// Small images that a test writes for a scene to read, in a temporary directory removed
// with the object. File names must be unique within the test process: lights and textures
// read images through a per-process cache keyed by path.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>

#include "image/image.h"

namespace ps::test {

struct TempImages {
    std::filesystem::path dir;
    explicit TempImages(const std::string& tag)
        : dir(std::filesystem::temp_directory_path() / ("pathspace-" + tag + "-" + std::to_string(getpid()))) {
        std::filesystem::create_directories(dir);
    }
    ~TempImages() { std::filesystem::remove_all(dir); }
    TempImages(const TempImages&) = delete;
    TempImages& operator=(const TempImages&) = delete;
    // Writes img as dir/name and returns the full path.
    std::string write(const std::string& name, const Image& img) const {
        std::string path = (dir / name).string();
        writeImage(path, img);
        return path;
    }
};

}  // namespace ps::test
