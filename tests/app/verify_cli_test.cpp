// `pathspace verify` through the real binary: an agreeing scene exits 0 with its report and
// map; a deliberately broken integrator (PATHSPACE_VERIFY_BREAK) is named, exits 3, and its
// blocks are the ones the report marks.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "render/mlt_scenes.h"
#include "run_binary.h"

namespace {

namespace fs = std::filesystem;

// A box every integrator samples (a light quad, coloured walls, a sphere).
const std::string kBox = ps::test::withBootstrap(ps::test::box("5 5 5", "0.7 0.2 0.2", "0.2 0.7 0.2"), 20000);

struct VerifyDir {
    fs::path dir = fs::temp_directory_path() / ("pathspace-verify-" + std::to_string(getpid()));
    VerifyDir() {
        fs::create_directories(dir);
        std::ofstream(dir / "box.pbrt") << kBox;
    }
    ~VerifyDir() { fs::remove_all(dir); }
    std::string args(const std::string& extra) const {
        return "verify " + (dir / "box.pbrt").string() + " --map " + (dir / "map.png").string() + " --json " +
               (dir / "report.json").string() + " --color rgb " + extra;
    }
    nlohmann::json report() const { return nlohmann::json::parse(std::ifstream(dir / "report.json")); }
};

TEST(VerifyCli, AgreeingSceneExitsZero) {
    VerifyDir d;
    const auto r = ps::test::runPathspace(d.args("--spp 32 --runs 8 --integrators path,light,bdpt,pssmlt"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("all 4 integrators agree"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::file_size(d.dir / "map.png") > 0);
    const auto j = d.report();
    EXPECT_TRUE(j["agree"].get<bool>());
    ASSERT_EQ(j["integrators"].size(), 4u);
    for (const auto& e : j["integrators"]) {
        EXPECT_TRUE(e["agrees"].get<bool>()) << e.dump();
        EXPECT_LT(e["resolution"].get<double>(), 0.05) << e.dump();  // it could have seen a 5% bias
    }
}

TEST(VerifyCli, BrokenIntegratorIsNamed) {
    VerifyDir d;
    // bdpt 3% too bright, everywhere.
    const auto r = ps::test::runCommand("PATHSPACE_VERIFY_BREAK=bdpt:1.03 " + std::string(PATHSPACE_BINARY) + " " +
                                        d.args("--spp 32 --runs 8 --integrators path,light,bdpt"));
    EXPECT_EQ(r.status, 3) << r.out;
    EXPECT_NE(r.out.find("1 of 3 differ: bdpt"), std::string::npos) << r.out;
    const auto j = d.report();
    EXPECT_FALSE(j["agree"].get<bool>());
    for (const auto& e : j["integrators"])
        EXPECT_EQ(e["agrees"].get<bool>(), e["integrator"] != "bdpt") << e.dump();
}

TEST(VerifyCli, LeavesOutWhatCannotBeSampledAndRefusesBadInput) {
    VerifyDir d;
    std::string ortho = kBox;
    ortho.replace(ortho.find("Camera \"perspective\""), 20, "Camera \"orthographic\"");
    std::ofstream(d.dir / "ortho.pbrt") << ortho;
    auto r = ps::test::runPathspace("verify " + (d.dir / "ortho.pbrt").string() +
                                    " --integrators path,light --spp 4 --runs 3 --map " + (d.dir / "m.png").string() +
                                    " --json " + (d.dir / "r.json").string());
    EXPECT_EQ(r.status, 3) << r.out;  // only path can render it of these two: nothing to compare
    EXPECT_NE(r.out.find("needs a perspective camera"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("nothing to compare"), std::string::npos) << r.out;
    r = ps::test::runPathspace(d.args("--integrators path,nope"));
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("unknown integrator \"nope\""), std::string::npos) << r.out;
    r = ps::test::runPathspace("verify " + (d.dir / "box.pbrt").string() + " --map " + d.dir.string());
    EXPECT_EQ(r.status, 2) << r.out;
}

}  // namespace
