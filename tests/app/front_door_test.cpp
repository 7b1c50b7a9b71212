// The command line as a newcomer from pbrt-v4 meets it, through the real binary: pbrt-v4's
// spellings, values that are options, outputs checked and compared before the render, the
// numbers' ranges, the summary and the statistics' honesty.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "image/image.h"
#include "run_binary.h"

namespace fs = std::filesystem;

namespace {

using ps::test::Result;
Result run(const std::string& args) { return ps::test::runPathspace(args); }

class FrontDoor : public ps::test::CliDirTest {
protected:
    void SetUp() override {
        CliDirTest::SetUp();
        scene = write("s.pbrt", kScene);
    }
    std::string at(const std::string& name) const { return (dir / name).string(); }
    static constexpr const char* kScene = ps::test::kSmallScene;
    std::string scene;
};

nlohmann::json readJson(const std::string& path) {
    std::ifstream f(path);
    return nlohmann::json::parse(f);
}

// `--stats --quiet` once wrote the statistics to a file named "--quiet": an option's value
// never starts with '-' (a negative number still reaches its own range check).
TEST_F(FrontDoor, AnOptionIsNeverAValue) {
    Result r = run("render " + scene + " -o --quiet");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.out.find("needs a value, not the option \"--quiet\""), std::string::npos) << r.out;
    r = run("render " + scene + " --spp 1 -o " + at("a.exr") + " --stats --quiet");
    EXPECT_EQ(r.status, 0) << r.out;  // pbrt-v4's --stats: printed, and --quiet honoured
    EXPECT_FALSE(fs::exists("--quiet"));
    EXPECT_FALSE(fs::exists(dir / "--quiet"));
    EXPECT_NE(r.out.find("\"rays\""), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("rendering ["), std::string::npos) << r.out;
    r = run("render " + scene + " --seed -1");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.out.find("whole number from 0"), std::string::npos) << r.out;
}

TEST_F(FrontDoor, PbrtSpellingsWork) {
    Result v = run("--version");
    EXPECT_EQ(v.status, 0);
    EXPECT_NE(v.out.find("pathspace "), std::string::npos) << v.out;
    // `pathspace scene.pbrt` is `pathspace render scene.pbrt`; pbrt-v4 puts options first.
    Result r = run("--spp 1 --nthreads 1 --quiet --outfile " + at("o.exr") + " " + scene);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_TRUE(fs::exists(dir / "o.exr"));
    r = run(scene + " --spp 1 --quiet -o " + at("p.exr"));
    EXPECT_EQ(r.status, 0) << r.out;
    // --cropwindow, the comma form of --crop and --pixelbounds choose the same pixels.
    for (const std::string& crop : {std::string("--cropwindow 0.25 0.75 0.5 1"), std::string("--crop 0.25,0.75,0.5,1"),
                                    std::string("--pixelbounds 8 24 12 24")}) {
        r = run(scene + " --spp 1 --quiet -o " + at("c.exr") + " " + crop);
        ASSERT_EQ(r.status, 0) << crop << "\n" << r.out;
        ps::Image img = ps::readImage(at("c.exr"));
        EXPECT_EQ(img.width, 16) << crop;
        EXPECT_EQ(img.height, 12) << crop;
        // As pbrt-v4 writes a crop: its data window inside the whole film's display window.
        EXPECT_EQ(img.filmWidth, 32) << crop;
        EXPECT_EQ(img.filmHeight, 24) << crop;
        EXPECT_EQ(img.x0, 8) << crop;
        EXPECT_EQ(img.y0, 12) << crop;
    }
    // pbrt-v4's --stats before the scene file is its flag, not a file to write over the scene.
    r = run("--stats --spp 1 --quiet -o " + at("s.exr") + " " + scene);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("\"integrator\": \"path\""), std::string::npos) << r.out;
    std::ifstream in(scene);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), {}), kScene);
}

TEST_F(FrontDoor, OutputsAreCheckedAndComparedBeforeRendering) {
    fs::create_directories(dir / "d.exr");
    struct Case {
        std::string args, says;
    };
    const Case cases[] = {
        {"-o " + at("d.exr"), "is a directory"},
        {"-o " + at("a.exr") + " --stats " + at("nodir/s.json"), "--stats"},
        {"-o " + at("a.exr") + " --stats " + at("d.exr"), "is a directory"},
        {"-o " + at("a.exr") + " --checkpoint " + at("nodir/c.ckpt"), "--checkpoint"},
        {"-o " + at("same.exr") + " --stats " + at("same.exr"), "name the same file"},
        {"-o " + at("w.pfm") + " -o " + at("w.variance.pfm") + " --aov variance", "name the same file"},
        {"-o " + at("x.exr") + " -o " + (dir / "." / "x.exr").string(), "name the same file"},
        {"-o " + at("y.exr") + " --checkpoint " + at("y.exr"), "name the same file"},
    };
    for (const Case& c : cases) {
        Result r = run("render --spp 1 " + scene + " " + c.args);
        EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
        EXPECT_NE(r.out.find(c.says), std::string::npos) << c.args << "\n" << r.out;
        EXPECT_EQ(r.out.find("rendering ["), std::string::npos) << c.args << ": refused only after rendering";
    }
    EXPECT_FALSE(fs::exists(dir / "a.exr"));
    EXPECT_FALSE(fs::exists(dir / "same.exr"));
}

TEST_F(FrontDoor, NumbersOutOfRangeAreErrors) {
    struct Case {
        std::string args, says;
    };
    const Case cases[] = {
        {"--seed 99999999999999999999", "whole number from 0 to 9223372036854775807"},
        {"--spp 1.5", "--spp: expected a whole number"},
        {"--threads 2.5", "--threads: expected a whole number"},
        {"--crop 0 1.5 0 1", "[0, 1]"},
        {"--crop 0.6 0.2 0 1", "x0 < x1"},
        {"--crop 0 1 0.5 0.5", "y0 < y1"},
        {"--pixelbounds 0 40 0 10", "<= 32"},
        {"--crop 0 1 0 1 --pixelbounds 0 4 0 4", "give one"},
    };
    for (const Case& c : cases) {
        Result r = run("render " + scene + " -o " + at("n.exr") + " " + c.args);
        EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
        EXPECT_NE(r.out.find(c.says), std::string::npos) << c.args << "\n" << r.out;
    }
}

TEST_F(FrontDoor, ThreadsBeyondTheMachineAreCutWithOneWarning) {
    // The threads a default render uses are the machine's (as the task scheduler sees it).
    Result r = run("render " + scene + " --spp 1 --quiet -o " + at("u.exr") + " --stats " + at("u.json"));
    EXPECT_EQ(r.status, 0) << r.out;
    const int cores = readJson(at("u.json"))["threads"].get<int>();  // the threads used, not 0
    EXPECT_GT(cores, 0);
    r = run("render " + scene + " --spp 1 --quiet --threads " + std::to_string(cores + 62) + " -o " + at("t.exr") +
            " --stats " + at("t.json"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("hardware threads; using " + std::to_string(cores)), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("TBB Warning"), std::string::npos) << r.out;
    EXPECT_EQ(readJson(at("t.json"))["threads"].get<int>(), cores);
}

TEST_F(FrontDoor, TheSummaryNamesWhatRanAndSaysWhatIsUnknown) {
    Result r = run("render " + scene + " --spp 1 -o " + at("a.exr") + " --stats " + at("a.json"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("integrator path (path tracing) | sampler independent | spectral colour |"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("noise estimate: n/a"), std::string::npos) << r.out;  // one sample: no variance
    EXPECT_TRUE(readJson(at("a.json"))["mean_relative_variance"].is_null());
    // A scene's Integrator "mlt" is pbrt-v4's multiplexed MLT: the summary says which ran.
    std::string mlt = std::string(kScene).insert(std::string(kScene).find("WorldBegin"),
                                                  "Integrator \"mlt\" \"integer mutationsperpixel\" [ 2 ] "
                                                  "\"integer bootstrapsamples\" [ 2000 ] \"integer chains\" [ 16 ]\n");
    r = run("render " + write("m.pbrt", mlt) + " --color rgb -o " + at("m.exr"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("integrator mmlt (multiplexed MLT: the scene's Integrator \"mlt\", pbrt-v4's) | rgb colour"),
              std::string::npos)
        << r.out;
    // Veach's mlt has no large or small steps; light tracing no camera paths.
    r = run("render " + scene + " --integrator mlt --spp 2 --bootstrap 2000 --chains 16 -o " + at("v.exr") + " --stats " +
            at("v.json"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out.find("large steps"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("per depth: share\n"), std::string::npos) << r.out;
    const nlohmann::json v = readJson(at("v.json"));
    EXPECT_FALSE(v["metropolis"].contains("large_steps"));
    EXPECT_FALSE(v["metropolis"].contains("sigma"));
    r = run("render " + scene + " --integrator light --spp 2 -o " + at("l.exr"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out.find("camera paths/s"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("light paths/s"), std::string::npos) << r.out;
}

TEST_F(FrontDoor, ASceneWithoutLightWarns) {
    std::string dark = std::string(kScene);
    dark.erase(dark.find("LightSource"), std::string("LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n").size());
    Result r = run("render " + write("dark.pbrt", dark) + " --spp 1 --quiet -o " + at("d.exr"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("no light source"), std::string::npos) << r.out;
}

TEST_F(FrontDoor, HelpFitsOneHundredColumnsInGroups) {
    Result r = run("render --help");
    EXPECT_EQ(r.status, 0);
    size_t longest = 0;
    for (size_t at = 0, end; at < r.out.size(); at = end + 1) {
        end = r.out.find('\n', at);
        if (end == std::string::npos) end = r.out.size();
        longest = std::max(longest, end - at);
    }
    EXPECT_LE(longest, 100u) << r.out;
    for (const char* group : {"Rendering:", "Output:", "Checkpoints:", "Metropolis (pssmlt, mmlt, mlt):"})
        EXPECT_NE(r.out.find(group), std::string::npos) << group;
}

TEST_F(FrontDoor, AMisspeltParameterSuggestsTheNearestKnownName) {
    std::string typo = std::string(kScene);
    typo.replace(typo.find("\"float radius\""), 14, "\"float radiuss\"");
    Result r = run("render " + write("typo.pbrt", typo) + " --spp 1 --quiet -o " + at("t.exr"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("unused parameter \"float radiuss\" in Shape \"sphere\" (did you mean \"radius\"?)"),
              std::string::npos)
        << r.out;
    // Nothing near: no suggestion.
    std::string odd = std::string(kScene);
    odd.replace(odd.find("\"float radius\""), 14, "\"float zzzzzzzzz\" [ 1 ] \"float radius\"");
    r = run("render " + write("odd.pbrt", odd) + " --spp 1 --quiet -o " + at("o.exr"));
    EXPECT_NE(r.out.find("unused parameter \"float zzzzzzzzz\""), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("did you mean"), std::string::npos) << r.out;
}

// After --resume the totals are the whole render's and the rates this run's; the efficiency,
// whose variance covers every run but whose time would be this run's, is not given. The
// checkpoint message says what the file holds: a render that ends keeps all of it.
TEST_F(FrontDoor, ResumedRendersSayWhatWasThisRunsAndCheckpointsWhatWasKept) {
    const std::string ckpt = at("c.ckpt");
    Result r = run("render " + scene + " --spp 1 -o " + at("a.exr") + " --checkpoint " + ckpt);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("checkpoint " + ckpt + " (1 written) holds 1 of 1 spp in every pixel"), std::string::npos)
        << r.out;
    r = run("render " + scene + " --spp 20000 --time 0.3 -o " + at("b.exr") + " --checkpoint " + ckpt +
            " --checkpoint-every 0 --stats " + at("b.json"));
    EXPECT_EQ(r.status, 0) << r.out;
    ASSERT_TRUE(fs::exists(ckpt)) << r.out;
    EXPECT_NE(r.out.find(" of 20000 spp in every pixel"), std::string::npos) << r.out;
    r = run("render " + scene + " --spp 20000 --time 0.3 -o " + at("b.exr") + " --resume " + ckpt + " --stats " +
            at("r.json"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("of them this run"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("efficiency n/a (resumed"), std::string::npos) << r.out;
    const nlohmann::json j = readJson(at("r.json"));
    EXPECT_TRUE(j["efficiency"].is_null());
    EXPECT_GT(j["resumed_spp"].get<int>(), 0);
    // The path tracer traces one camera path per sample: its rate is this run's samples over
    // this run's time, not the whole render's.
    const double thisRun = j["rank_samples"][0].get<double>();
    EXPECT_NEAR(j["camera_paths_per_s"].get<double>() * j["wall_time_s"].get<double>(), thisRun, 1e-6 * thisRun);
    EXPECT_GT(j["camera_paths"].get<double>(), 1.01 * thisRun);
}

// A Metropolis render in a time budget shorter than its bootstrap would take shrinks the
// bootstrap to a quarter of the budget instead of overrunning it; its start-up shows progress.
TEST_F(FrontDoor, MetropolisStartUpFitsTheTimeBudgetAndShowsProgress) {
    for (const std::string integrator : {"mmlt", "mlt"}) {
        SCOPED_TRACE(integrator);
        const auto start = std::chrono::steady_clock::now();
        const std::string common = "render " + scene + " --integrator " + integrator +
                                   " --spp 100000 --time 1 --bootstrap 50000000 --two-stage 0.1 -o " + at("t.exr");
        const Result r = run(common + " --stats " + at("t.json") + " --checkpoint " + at("t.ckpt"));
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_EQ(r.status, 0) << r.out;
        EXPECT_NE(r.out.find("bootstrap [="), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("budget; fewer bootstrap samples"), std::string::npos) << r.out;
        const nlohmann::json j = readJson(at("t.json"));
        const long long boot = j["metropolis"]["bootstrap_samples"].get<long long>();
        std::printf("%s: --time 1: %.2f s in all, %lld bootstrap samples\n", integrator.c_str(), seconds, boot);
        EXPECT_LT(boot, 50000000);
        EXPECT_LT(j["metropolis"]["two_stage_samples"].get<long long>(), 5000000);
        EXPECT_GT(j["metropolis"]["mutations"].get<long long>(), 0);
        // The whole render (the scene's loading and the image's writing included) near its
        // budget: at the full bootstrap it takes minutes.
        EXPECT_LT(seconds, 10.0);
        // Its checkpoint holds the cut bootstrap and pilot map (whose tiles follow the pilot's
        // samples): resumed, the chains go on from it.
        const Result resumed = run(common + " --resume " + at("t.ckpt"));
        EXPECT_EQ(resumed.status, 0) << resumed.out;
        EXPECT_EQ(resumed.out.find("bootstrap [="), std::string::npos) << resumed.out;
    }
}

// Reading warns as it parses; building warns later about what parsing kept (an unused
// parameter): the user reads them in file order all the same.
TEST_F(FrontDoor, WarningsComeOutInFileOrder) {
    std::string text = std::string(kScene);
    text.replace(text.find("\"float fov\" [ 30 ]"), 19, "\"float fov\" [ 30 ] \"float fovv\" [ 1 ]");
    text += "AttributeEnd\n";
    Result r = run("render " + write("order.pbrt", text) + " --spp 1 --quiet -o " + at("w.exr"));
    EXPECT_EQ(r.status, 0) << r.out;
    const size_t early = r.out.find("unused parameter \"float fovv\""), late = r.out.find("AttributeEnd without");
    ASSERT_NE(early, std::string::npos) << r.out;
    ASSERT_NE(late, std::string::npos) << r.out;
    EXPECT_LT(early, late) << r.out;
}

}  // namespace
