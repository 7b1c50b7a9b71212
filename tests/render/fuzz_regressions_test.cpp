// Replays every input the fuzz targets ever crashed on (fuzz/regressions/<target>/) and the
// seed corpora (fuzz/corpus/), through the same byte-to-reader mapping the targets use
// (fuzz/fuzz_inputs.h). Each must load or fail with InputError; a crash or any other
// exception fails the test. Built with the normal compiler, and with sanitizers in
// scripts/test-sanitizers.sh.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz_inputs.h"

namespace fs = std::filesystem;

namespace {

using Runner = void (*)(const uint8_t*, size_t);

std::vector<fs::path> filesIn(const fs::path& dir) {
    std::vector<fs::path> files;
    if (fs::is_directory(dir))
        for (const auto& e : fs::directory_iterator(dir))
            if (e.is_regular_file() && e.path().filename() != ".gitkeep") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

void replay(const std::string& target, const std::string& corpus, Runner run) {
    ps::setWarningsQuiet(true);
    const fs::path root = PATHSPACE_SOURCE_DIR "/fuzz";
    std::vector<fs::path> files = filesIn(root / "regressions" / target);
    std::vector<fs::path> seeds = filesIn(root / "corpus" / corpus);
    files.insert(files.end(), seeds.begin(), seeds.end());
    ASSERT_FALSE(seeds.empty()) << "no seed corpus in " << (root / "corpus" / corpus);
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.string());
        std::ifstream in(file, std::ios::binary);
        std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        EXPECT_NO_THROW(run(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
    }
}

}  // namespace

TEST(FuzzRegressions, Scene) { replay("scene_fuzzer", "scene", ps::fuzz::runSceneInput); }
TEST(FuzzRegressions, Ply) { replay("ply_fuzzer", "ply", ps::fuzz::runPlyInput); }
TEST(FuzzRegressions, Image) { replay("image_fuzzer", "image", ps::fuzz::runImageInput); }
TEST(FuzzRegressions, NanoVDB) { replay("nvdb_fuzzer", "nvdb", ps::fuzz::runNanoVDBInput); }
