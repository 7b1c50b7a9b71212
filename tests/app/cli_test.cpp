// End-to-end tests of the pathspace command: exit codes, outputs, statistics, options.
// (Early stops: interrupt_test.cpp.)
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "image/image.h"
#include "mc/sampler.h"
#include "furnace_scene.h"
#include "run_binary.h"
#include "sky_scene.h"

namespace fs = std::filesystem;

namespace {

using ps::test::Result;
Result run(const std::string& args) { return ps::test::runPathspace(args); }

class Cli : public ps::test::CliDirTest {};

using ps::test::kSmallScene;

}  // namespace

TEST_F(Cli, HelpDocumentsEveryOption) {
    Result r = run("--help");
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("render"), std::string::npos);
    Result rr = run("render --help");
    EXPECT_EQ(rr.status, 0);
    for (const char* opt : {"--spp", "--time", "--threads", "--seed", "--integrator", "--output", "--crop", "--stats", "--quiet",
                            "--chains", "--bootstrap", "--large-step-probability", "--sigma"})
        EXPECT_NE(rr.out.find(opt), std::string::npos) << opt;
}

TEST_F(Cli, MissingSceneIsBadInput) {
    Result r = run("render " + (dir / "nope.pbrt").string());
    EXPECT_EQ(r.status, 2);
}

TEST_F(Cli, SyntaxErrorNamesFileLineColumn) {
    std::string scene = write("bad.pbrt", "LookAt 0 0 5  0 0 0  0 1 0\nWorldBegin\n  Shape \"sphere\" \"float radius [ 1 ]\n");
    Result r = run("render --quiet " + scene);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.out.find("bad.pbrt:3:"), std::string::npos) << r.out;
}

TEST_F(Cli, UnwritableOutputFailsBeforeRendering) {
    std::string scene = write("s.pbrt", kSmallScene);
    Result r = run("render --quiet --spp 100000 " + scene + " -o /nonexistent-dir/x.exr");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.out.find("/nonexistent-dir"), std::string::npos) << r.out;
    Result r2 = run("render --quiet " + scene + " -o " + (dir / "x.tga").string());
    EXPECT_EQ(r2.status, 2);
}

TEST_F(Cli, RendersToFilmFilenameAndWritesStats) {
    std::string scene = write("s.pbrt", kSmallScene);
    std::string cmd = "cd " + dir.string() + " && " + PATHSPACE_BINARY + " render --quiet --stats stats.json s.pbrt";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    ASSERT_TRUE(fs::exists(dir / "small.exr"));
    ps::Image img = ps::readImage((dir / "small.exr").string());
    EXPECT_EQ(img.width, 32);
    EXPECT_EQ(img.height, 24);
    nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "stats.json"));
    for (const char* k : {"wall_time_s", "spp_mean", "camera_paths_per_s", "rays", "rays_per_s"})
        EXPECT_TRUE(j.contains(k)) << k;
    EXPECT_EQ(j["spp_mean"].get<double>(), 4.0);
    EXPECT_EQ(j["camera_paths"].get<long long>(), 32 * 24 * 4);
}

// The summary a successful render prints has no line a newcomer (or grep "error:") takes for
// an error message: the variance estimate is labelled "noise estimate".
TEST_F(Cli, SummaryOfASuccessfulRenderHasNoErrorLine) {
    std::string scene = write("s.pbrt", kSmallScene);
    Result r = run("render " + scene + " -o " + (dir / "x.pfm").string());
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("\nnoise estimate: mean relative variance "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("error:"), std::string::npos) << r.out;
}

// Film "maxcomponentvalue" makes the image biased: the summary and the statistics say so, and
// say nothing of a clamp when there is none.
TEST_F(Cli, ClampIsReportedAsBiased) {
    std::string text = kSmallScene;
    const std::string film = R"("string filename" [ "small.exr" ])";
    const std::string clampedScene = write("c.pbrt", text.replace(text.find(film), film.size(),
                                                                   film + R"( "float maxcomponentvalue" [ 2 ])"));
    const std::string plainScene = write("s.pbrt", kSmallScene);
    const std::string clampedStats = (dir / "c.json").string(), plainStats = (dir / "s.json").string();
    Result c = run("render " + clampedScene + " --stats " + clampedStats + " -o " + (dir / "c.pfm").string());
    Result p = run("render " + plainScene + " --stats " + plainStats + " -o " + (dir / "s.pfm").string());
    ASSERT_EQ(c.status, 0) << c.out;
    ASSERT_EQ(p.status, 0) << p.out;
    EXPECT_NE(c.out.find("\nclamp: Film \"maxcomponentvalue\" 2 (biased"), std::string::npos) << c.out;
    EXPECT_EQ(p.out.find("clamp:"), std::string::npos) << p.out;
    const auto cj = nlohmann::json::parse(std::ifstream(clampedStats)), pj = nlohmann::json::parse(std::ifstream(plainStats));
    ASSERT_TRUE(cj.contains("max_component_value"));
    EXPECT_EQ(cj["max_component_value"]["value"].get<double>(), 2.0);
    EXPECT_NE(cj["max_component_value"]["note"].get<std::string>().find("biased"), std::string::npos);
    EXPECT_FALSE(pj.contains("max_component_value"));
}

TEST_F(Cli, SeveralOutputsAndCrop) {
    std::string scene = write("s.pbrt", kSmallScene);
    std::string exr = (dir / "a.exr").string(), png = (dir / "a.png").string(), pfm = (dir / "a.pfm").string();
    Result r = run("render --quiet --crop 0.25 0.75 0 0.5 " + scene + " -o " + exr + " -o " + png + " -o " + pfm);
    ASSERT_EQ(r.status, 0) << r.out;
    ps::Image a = ps::readImage(exr), b = ps::readImage(pfm);
    EXPECT_EQ(a.width, 16);
    EXPECT_EQ(a.height, 12);
    EXPECT_EQ(a.rgb, b.rgb);
    EXPECT_TRUE(fs::exists(png));
}

TEST_F(Cli, McWritesJsonAndSvgAndRejectsUnknownNames) {
    std::string json = (dir / "mc.json").string(), svg = (dir / "mc.svg").string();
    Result r = run("mc --integrand exp --dims 2 --n 64 128 256 --runs 8 --json " + json + " --svg " + svg);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("| independent |"), std::string::npos) << r.out;
    std::ifstream in(json);
    nlohmann::json j = nlohmann::json::parse(in);  // throws if malformed
    EXPECT_EQ(j["runs"], 8);
    EXPECT_EQ(j["n"], nlohmann::json({64, 128, 256}));
    ASSERT_EQ(j["results"].size(), 1u);
    const nlohmann::json& res = j["results"][0];
    EXPECT_EQ(res["integrand"], "exp");
    EXPECT_EQ(res["dims"], 2);
    EXPECT_NEAR(res["exact"].get<double>(), (M_E - 1) * (M_E - 1), 1e-12);
    ASSERT_GE(res["techniques"].size(), 10u);
    for (const nlohmann::json& t : res["techniques"]) {
        EXPECT_TRUE(t.contains("name") && t.contains("slope"));
        ASSERT_EQ(t["points"].size(), 3u) << t["name"];
        for (const char* key : {"n", "evaluations", "mean", "standard_error", "rmse", "seconds", "efficiency"})
            EXPECT_TRUE(t["points"][0].contains(key)) << key;
    }
    std::ifstream s(svg);
    std::string text((std::istreambuf_iterator<char>(s)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.rfind("<svg", 0), 0u);
    EXPECT_NE(text.find("<polyline"), std::string::npos);
    EXPECT_NE(text.find("</svg>"), std::string::npos);

    EXPECT_EQ(run("mc --integrand nope").status, 2);
    EXPECT_EQ(run("mc --technique nope").status, 2);
    EXPECT_EQ(run("mc --dims 11").status, 2);
    Result help = run("mc --help");
    EXPECT_EQ(help.status, 0);
    for (const char* opt : {"--integrand", "--dims", "--technique", "--n", "--runs", "--seed", "--json", "--svg"})
        EXPECT_NE(help.out.find(opt), std::string::npos) << opt;
}

TEST_F(Cli, BdptStrategyImagesAndIntegratorChecks) {
    std::string scene = write("s.pbrt", kSmallScene);
    fs::path strategies = dir / "strategies";
    Result r = run("render --quiet --integrator bdpt --maxdepth 2 --bdpt-strategies " + strategies.string() + " " + scene +
                   " -o " + (dir / "b.exr").string());
    ASSERT_EQ(r.status, 0) << r.out;
    // Depths 0..2: (0,2); (0,3) (1,2) (2,1); (0,4) (1,3) (2,2) (3,1), weighted and unweighted.
    for (const char* name : {"s0_t2", "s0_t3", "s1_t2", "s2_t1", "s0_t4", "s1_t3", "s2_t2", "s3_t1"}) {
        EXPECT_TRUE(fs::exists(strategies / (std::string(name) + ".exr"))) << name;
        EXPECT_TRUE(fs::exists(strategies / (std::string(name) + "_unweighted.exr"))) << name;
    }
    ps::Image s = ps::readImage((strategies / "s1_t2.exr").string());
    EXPECT_EQ(s.width, 32);
    // Every depth up to maxdepth, beyond the 5 of earlier versions: depth 6 has (0,8) .. (7,1).
    const fs::path deep = dir / "deep";
    ASSERT_EQ(run("render --quiet --integrator bdpt --spp 1 --maxdepth 6 --bdpt-strategies " + deep.string() + " " +
                  scene + " -o " + (dir / "d.exr").string())
                  .status,
              0);
    for (const char* name : {"s0_t8", "s3_t5", "s7_t1"}) EXPECT_TRUE(fs::exists(deep / (std::string(name) + ".exr"))) << name;
    EXPECT_FALSE(fs::exists(deep / "s0_t9.exr"));
    // Through a thin lens also the t = 0 strategies (light subpaths that cross the lens), from depth 1.
    std::string lensScene = kSmallScene;
    lensScene.insert(lensScene.find("[ 30 ]") + 6, " \"float lensradius\" [ 0.1 ] \"float focaldistance\" [ 5 ]");
    const fs::path lens = dir / "lens";
    ASSERT_EQ(run("render --quiet --integrator bdpt --spp 1 --maxdepth 2 --bdpt-strategies " + lens.string() + " " +
                  write("lens.pbrt", lensScene) + " -o " + (dir / "lens.exr").string())
                  .status,
              0);
    for (const char* name : {"s3_t0", "s3_t0_unweighted", "s4_t0", "s4_t0_unweighted", "s2_t1"})
        EXPECT_TRUE(fs::exists(lens / (std::string(name) + ".exr"))) << name;
    EXPECT_FALSE(fs::exists(lens / "s2_t0.exr"));
    EXPECT_FALSE(fs::exists(strategies / "s3_t0.exr"));  // a pinhole has none
    // Strategy images only come from BDPT; light tracing needs a perspective camera.
    Result wrong = run("render --quiet --integrator path --bdpt-strategies " + strategies.string() + " " + scene);
    EXPECT_EQ(wrong.status, 2);
    EXPECT_NE(wrong.out.find("--integrator bdpt"), std::string::npos) << wrong.out;
    std::string ortho = write("o.pbrt", std::string(kSmallScene).replace(std::string(kSmallScene).find("perspective"), 11,
                                                                           "orthographic"));
    Result o = run("render --quiet --integrator light " + ortho + " -o " + (dir / "o.exr").string());
    EXPECT_EQ(o.status, 2);
    EXPECT_NE(o.out.find("perspective"), std::string::npos) << o.out;
    Result l = run("render --quiet --integrator light --spp 2 " + scene + " -o " + (dir / "l.exr").string());
    EXPECT_EQ(l.status, 0) << l.out;
}

TEST_F(Cli, VarianceAovNextToEachOutput) {
    std::string scene = write("s.pbrt", kSmallScene);
    std::string exr = (dir / "v.exr").string(), png = (dir / "v.png").string();
    Result r = run("render --quiet --aov variance --crop 0.25 0.75 0 0.5 " + scene + " -o " + exr + " -o " + png);
    ASSERT_EQ(r.status, 0) << r.out;
    ASSERT_TRUE(fs::exists(dir / "v.variance.exr"));
    ASSERT_TRUE(fs::exists(dir / "v.variance.png"));
    ps::Image v = ps::readImage((dir / "v.variance.exr").string());
    EXPECT_EQ(v.width, 16);
    EXPECT_EQ(v.height, 12);
    double sum = 0;
    for (float x : v.rgb) {
        EXPECT_GE(x, 0.0f);
        sum += x;
    }
    EXPECT_GT(sum, 0.0);  // 4 independent samples per pixel of a lit sphere: not exact
    EXPECT_FALSE(fs::exists(dir / "small.variance.exr"));
    EXPECT_EQ(run("render --quiet --aov depth " + scene + " -o " + exr).status, 2);
}

TEST_F(Cli, AdaptiveSampling) {
    std::string scene = write("s.pbrt", kSmallScene);
    Result help = run("render --help");
    for (const char* s : {"--adaptive", "sequential", "twostage", "BIASED", "--aov"})
        EXPECT_NE(help.out.find(s), std::string::npos) << s;
    for (const char* mode : {"sequential", "twostage"}) {
        std::string out = (dir / "a.exr").string(), stats = (dir / "a.json").string();
        Result r = run(std::string("render --quiet --spp 16 --adaptive ") + mode + " --stats " + stats + " " + scene +
                       " -o " + out);
        ASSERT_EQ(r.status, 0) << r.out;
        nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
        EXPECT_EQ(j["adaptive"].get<std::string>(), mode);
        EXPECT_NEAR(j["spp_mean"].get<double>(), 16.0, 0.5);
        EXPECT_EQ(ps::readImage(out).width, 32);
    }
    Result light = run("render --quiet --adaptive twostage --integrator light " + scene + " -o " + (dir / "l.exr").string());
    EXPECT_EQ(light.status, 2);
    EXPECT_NE(light.out.find("--integrator path"), std::string::npos) << light.out;
    EXPECT_FALSE(fs::exists(dir / "l.exr"));
    EXPECT_EQ(run("render --quiet --adaptive sequential --integrator bdpt " + scene + " -o " + (dir / "b.exr").string()).status, 2);
}

// --max-memory: the film, textures and meshes are checked against it before they are
// allocated; the error names the input, what it needs and the limit.
TEST_F(Cli, MaxMemoryLimitsWhatARenderMayAllocate) {
    const std::string cornell = std::string(PATHSPACE_SOURCE_DIR) + "/scenes/cornell-box.pbrt";
    const std::string out = (dir / "c.exr").string();
    Result r = run("render --quiet --max-memory 1M " + cornell + " -o " + out);
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("cornell-box.pbrt:9:1: error: Film 400x400 needs "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" MiB of memory, more than the limit of 1.0 MiB (raise it with --max-memory)"), std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(out));

    for (const char* bad : {"banana", "0", "-5G", "12Q"}) {
        Result b = run(std::string("render --quiet --max-memory ") + bad + " " + cornell + " -o " + out);
        EXPECT_EQ(b.status, 2) << bad;
        EXPECT_NE(b.out.find(std::string("--max-memory: expected a size such as 512M, 8G or 1.5GiB, got \"") + bad + "\""),
                  std::string::npos)
            << b.out;
    }
    Result help = run("render --help");
    EXPECT_NE(help.out.find("--max-memory"), std::string::npos);
    EXPECT_NE(help.out.find("80% of physical"), std::string::npos);

    // A texture beyond the limit, named by its file; the limit is in the statistics.
    ps::Image tex(256, 256);
    ps::writeImage((dir / "tex.png").string(), tex);
    std::string scene = std::string(kSmallScene) + "";
    scene.replace(scene.find("Material \"diffuse\""), 18,
                  "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"tex.png\"\n"
                  "Material \"diffuse\" \"texture reflectance\" \"t\"");
    std::string textured = write("t.pbrt", scene);
    Result t = run("render --quiet --max-memory 512K " + textured + " -o " + out);
    EXPECT_EQ(t.status, 2) << t.out;
    EXPECT_NE(t.out.find("tex.png: image 256x256 needs 1.0 MiB of memory, more than the limit of 512.0 KiB"),
              std::string::npos)
        << t.out;
    std::string stats = (dir / "s.json").string();
    Result ok = run("render --quiet --max-memory 2M --stats " + stats + " " + textured + " -o " + out);
    ASSERT_EQ(ok.status, 0) << ok.out;
    nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
    EXPECT_EQ(j["memory_limit_bytes"].get<uint64_t>(), uint64_t(2) << 20);
}

// --seed and --threads reach the renderer: another seed gives another image, another thread
// count the same bits (every pixel sample has its own random stream; BDPT's splats add up in
// fixed point), and the statistics record both.
TEST_F(Cli, SeedAndThreadsOptions) {
    const std::string scene = write("s.pbrt", kSmallScene);
    auto render = [&](const std::string& integrator, int seed, int threads) {
        const std::string out = (dir / "x.pfm").string(), stats = (dir / "x.json").string();
        fs::remove(out);
        Result r = run("render --quiet --spp 4 --integrator " + integrator + " --seed " + std::to_string(seed) +
                       " --threads " + std::to_string(threads) + " --stats " + stats + " " + scene + " -o " + out);
        EXPECT_EQ(r.status, 0) << r.out;
        nlohmann::json j = nlohmann::json::parse(std::ifstream(stats));
        EXPECT_EQ(j["seed"].get<long long>(), seed);
        EXPECT_EQ(j["threads"].get<int>(), threads);
        return ps::readImage(out).rgb;
    };
    for (const std::string integrator : {"path", "bdpt"}) {
        SCOPED_TRACE(integrator);
        // Two threads: more than the machine has would be cut to its count (FrontDoor).
        std::vector<float> a = render(integrator, 5, 1), b = render(integrator, 5, 2), c = render(integrator, 6, 2);
        EXPECT_EQ(a, b) << "the thread count changed the image";
        EXPECT_NE(a, c) << "the seed did not change the image";
    }
}

// Every --sampler name is accepted and reaches the renderer: the statistics name it and each
// placement gives its own image. Unknown names are bad input (status 2).
TEST_F(Cli, SamplerOption) {
    const std::string scene = write("s.pbrt", kSmallScene);
    const std::string out = (dir / "x.pfm").string(), stats = (dir / "x.json").string();
    std::vector<std::vector<float>> images;
    for (const std::string& name : ps::samplerNames()) {
        SCOPED_TRACE(name);
        fs::remove(out);
        Result r = run("render --quiet --spp 4 --seed 1 --sampler " + name + " --stats " + stats + " " + scene + " -o " + out);
        ASSERT_EQ(r.status, 0) << r.out;
        EXPECT_EQ(nlohmann::json::parse(std::ifstream(stats))["sampler"].get<std::string>(), name);
        images.push_back(ps::readImage(out).rgb);
        for (size_t k = 0; k + 1 < images.size(); ++k)
            EXPECT_NE(images[k], images.back()) << "same image as " << ps::samplerNames()[k];
    }
    EXPECT_GE(images.size(), 7u);
    Result bad = run("render --quiet --sampler nope " + scene + " -o " + out);
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.out.find("nope"), std::string::npos) << bad.out;
}

// --mis changes how BDPT weights its strategies but never the expected image: power, balance
// and none (uniform) give different images, each exact within noise (uniform weights are
// the noisiest: 1024 samples per pixel resolve 1% with them).
TEST_F(Cli, MisOption) {
    const std::string scene = write("sky.pbrt", ps::test::kSkyScene);
    const std::string out = (dir / "x.pfm").string();
    std::vector<std::vector<float>> images;
    for (const std::string mis : {"power", "balance", "none"}) {
        SCOPED_TRACE(mis);
        fs::remove(out);
        Result r = run("render --quiet --integrator bdpt --spp 1024 --seed 1 --mis " + mis + " " + scene + " -o " + out);
        ASSERT_EQ(r.status, 0) << r.out;
        ps::Image img = ps::readImage(out);
        ps::test::expectExactSkyImage(img, "--mis " + mis);
        images.push_back(img.rgb);
        for (size_t k = 0; k + 1 < images.size(); ++k) EXPECT_NE(images[k], images.back()) << "same image as #" << k;
    }
    EXPECT_EQ(run("render --quiet --integrator bdpt --mis nope " + scene + " -o " + out).status, 2);
}

// --light-paths F: a share F of BDPT's camera samples are BDPT samples, the rest path
// tracing's. Exact on
// the sky scene at 0.25 (its unbiasedness against path tracing: render/estimator_agreement_test),
// a different image from the default, the share in --stats; outside (0, 1] or with another
// integrator it exits with 2 and says why.
TEST_F(Cli, LightPathsOption) {
    const std::string scene = write("sky.pbrt", ps::test::kSkyScene);
    const std::string out = (dir / "x.pfm").string(), stats = (dir / "s.json").string();
    const std::string base = "render --quiet --seed 1 " + scene + " -o " + out;
    Result r = run(base + " --integrator bdpt --spp 1024 --light-paths 0.25 --stats " + stats);
    ASSERT_EQ(r.status, 0) << r.out;
    const ps::Image fewer = ps::readImage(out);
    ps::test::expectExactSkyImage(fewer, "--light-paths 0.25");
    std::ifstream in(stats);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_FLOAT_EQ(j.at("light_paths_per_sample").get<float>(), 0.25f);
    ASSERT_EQ(run(base + " --integrator bdpt --spp 1024").status, 0);
    EXPECT_NE(ps::readImage(out).rgb, fewer.rgb);
    for (const std::string bad : {"0", "-0.5", "1.5", "x"}) {
        Result b = run(base + " --integrator bdpt --spp 1 --light-paths " + bad);
        EXPECT_EQ(b.status, 2) << bad;
        EXPECT_NE(b.out.find("--light-paths"), std::string::npos) << b.out;
    }
    Result path = run(base + " --integrator path --spp 1 --light-paths 0.5");
    EXPECT_EQ(path.status, 2);
    EXPECT_NE(path.out.find("needs --integrator bdpt"), std::string::npos) << path.out;
    // The path tracer's samples have no strategies (s, t) to draw.
    Result images = run(base + " --integrator bdpt --spp 1 --light-paths 0.5 --bdpt-strategies " + (dir / "st").string());
    EXPECT_EQ(images.status, 2);
    EXPECT_NE(images.out.find("--bdpt-strategies needs every sample to be a BDPT sample"), std::string::npos) << images.out;
    // --stats names them as a technique of their own.
    bool pathTechnique = false;
    for (const auto& k : j.at("techniques").at("list")) pathTechnique = pathTechnique || k.at("name") == "path";
    EXPECT_TRUE(pathTechnique) << j.at("techniques").dump();
}

// --light-paths auto: a pilot of each kind of sample chooses the share, which the summary line
// and --stats report; the exact sky image either way. It cannot resume (its choice is timed)
// and applies to BDPT alone.
TEST_F(Cli, LightPathsAuto) {
    const std::string scene = write("sky.pbrt", ps::test::kSkyScene);
    const std::string out = (dir / "x.pfm").string(), stats = (dir / "s.json").string();
    const std::string base = "render --seed 1 " + scene + " -o " + out;
    Result r = run(base + " --integrator bdpt --spp 1024 --light-paths auto --stats " + stats);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("(auto)"), std::string::npos) << r.out;
    ps::test::expectExactSkyImage(ps::readImage(out), "--light-paths auto");
    std::ifstream in(stats);
    const nlohmann::json j = nlohmann::json::parse(in);
    const float share = j.at("light_paths_per_sample").get<float>();
    EXPECT_TRUE(share == 0 || share == 1) << share;  // no delta lights: 0 where path tracing wins
    EXPECT_GT(j.at("light_paths_auto").at("path_variance_time").get<double>(), 0);
    EXPECT_GT(j.at("light_paths_auto").at("bdpt_variance_time").get<double>(), 0);
    const std::string checkpoint = (dir / "c.ckpt").string();
    ASSERT_EQ(run(base + " --quiet --integrator bdpt --spp 2 --checkpoint " + checkpoint).status, 0);
    Result resume = run(base + " --integrator bdpt --spp 4 --light-paths auto --resume " + checkpoint);
    EXPECT_EQ(resume.status, 2);
    EXPECT_NE(resume.out.find("--light-paths auto cannot resume"), std::string::npos) << resume.out;
    Result path = run(base + " --integrator path --spp 1 --light-paths auto");
    EXPECT_EQ(path.status, 2);
    EXPECT_NE(path.out.find("needs --integrator bdpt"), std::string::npos) << path.out;
}

// Shadow-ray roulette through the real binary: the exact sky image with most shadow rays
// left out (counted in --stats), and refusals where it has no meaning.
TEST_F(Cli, ShadowRouletteOption) {
    const std::string scene = write("sky.pbrt", ps::test::kSkyScene);
    const std::string out = (dir / "x.pfm").string(), stats = (dir / "s.json").string();
    const std::string base = "render --quiet --seed 1 " + scene + " -o " + out;
    for (const std::string integrator : {"path", "bdpt"}) {
        SCOPED_TRACE(integrator);
        Result r = run(base + " --integrator " + integrator + " --spp 1024 --shadow-roulette 3 --stats " + stats);
        ASSERT_EQ(r.status, 0) << r.out;
        const ps::Image image = ps::readImage(out);
        ps::test::expectExactSkyImage(image, "--shadow-roulette 3");
        std::ifstream in(stats);
        const nlohmann::json j = nlohmann::json::parse(in);
        EXPECT_FLOAT_EQ(j.at("shadow_roulette").get<float>(), 3.0f);
        EXPECT_GT(j.at("shadow_rays_skipped").get<double>(), 0.2 * j.at("shadow_rays").get<double>());
        ASSERT_EQ(run(base + " --integrator " + integrator + " --spp 1024").status, 0);
        EXPECT_NE(ps::readImage(out).rgb, image.rgb);
    }
    for (const std::string bad : {"-1", "x", "1000"}) {
        Result b = run(base + " --spp 1 --shadow-roulette " + bad);
        EXPECT_EQ(b.status, 2) << bad;
        EXPECT_NE(b.out.find("--shadow-roulette"), std::string::npos) << b.out;
    }
    for (const std::string refused : {"--integrator mlt", "--integrator pssmlt", "--adaptive sequential"}) {
        Result b = run(base + " --spp 4 --shadow-roulette 0.5 " + refused);
        EXPECT_EQ(b.status, 2) << refused;
        EXPECT_NE(b.out.find("--shadow-roulette"), std::string::npos) << refused << ": " << b.out;
    }
}

// Every heuristic of thesis ch. 9 through the real binary (their unbiasedness is the
// furnace's, render/mis_heuristics_test.cpp): accepted by path, bdpt, pssmlt and mmlt, each
// changing the image; a bad parameter, or --mis where nothing is weighted (light, mlt) or
// only balance applies (path with media), exits with 2 and says why.
TEST_F(Cli, EveryMisHeuristicAndItsRefusals) {
    const std::string scene = write("sky.pbrt", ps::test::kSkyScene);
    const std::string out = (dir / "x.pfm").string(), stats = (dir / "s.json").string();
    const std::string base = "render --quiet --spp 2 --seed 1 " + scene + " -o " + out;
    for (const std::string integrator : {"path", "bdpt"}) {
        std::vector<std::vector<float>> images;
        for (const std::string mis : {"power", "balance", "power:3", "cutoff", "cutoff:0.5", "maximum", "none"}) {
            SCOPED_TRACE(integrator + " --mis " + mis);
            Result r = run(base + " --integrator " + integrator + " --mis " + mis);
            ASSERT_EQ(r.status, 0) << r.out;
            images.push_back(ps::readImage(out).rgb);
            for (size_t k = 0; k + 1 < images.size(); ++k) EXPECT_NE(images[k], images.back()) << "same image as #" << k;
        }
        // power:2 is the default, spelled out.
        ASSERT_EQ(run(base + " --integrator " + integrator + " --mis power:2").status, 0);
        EXPECT_EQ(ps::readImage(out).rgb, images[0]);
    }
    for (const std::string integrator : {"pssmlt", "mmlt"}) {
        Result r = run(base + " --integrator " + integrator + " --chains 4 --bootstrap 200 --mis maximum");
        EXPECT_EQ(r.status, 0) << integrator << ": " << r.out;
    }
    for (const std::string bad : {"power:0", "power:-1", "power:x", "cutoff:2", "maximum:1", "max"}) {
        Result r = run(base + " --integrator bdpt --mis " + bad);
        EXPECT_EQ(r.status, 2) << bad;
        EXPECT_NE(r.out.find("--mis"), std::string::npos) << r.out;
    }
    for (const std::string integrator : {"light", "mlt"}) {
        Result r = run(base + " --integrator " + integrator + " --mis balance");
        EXPECT_EQ(r.status, 2) << integrator;
        EXPECT_NE(r.out.find("combines no sampling techniques"), std::string::npos) << r.out;
        const std::string chains = integrator == "mlt" ? " --chains 4 --bootstrap 200" : "";
        EXPECT_EQ(run(base + " --integrator " + integrator + chains).status, 0) << integrator;
    }
    const std::string fog = write("fog.pbrt", ps::test::kFogFurnace);
    Result media = run("render --quiet --spp 1 " + fog + " -o " + out + " --mis power");
    EXPECT_EQ(media.status, 2);
    EXPECT_NE(media.out.find("only --mis balance applies"), std::string::npos) << media.out;
    EXPECT_EQ(run("render --quiet --spp 1 " + fog + " -o " + out + " --mis balance").status, 0);
}

// `pathspace mc --study mis`: the glossy-highlight study prints every heuristic's variance
// and efficiency and writes them as JSON; an unknown study is bad input.
TEST_F(Cli, McMisStudy) {
    const std::string json = (dir / "mis.json").string();
    Result r = run("mc --study mis --n 2000 --seed 3 --json " + json);
    ASSERT_EQ(r.status, 0) << r.out;
    for (const char* name : {"| balance |", "| power:2 |", "| cutoff:0.1 |", "| maximum |", "| light alone |",
                             "| bsdf alone |", "Relative variance", "Efficiency"})
        EXPECT_NE(r.out.find(name), std::string::npos) << name << "\n" << r.out;
    nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j["samples"], 2000);
    ASSERT_EQ(j["cases"].size(), 16u);
    for (const char* name : {"balance", "power:2", "cutoff:0.1", "maximum", "light alone", "bsdf alone"})
        EXPECT_TRUE(j["cases"][0]["strategies"].contains(name)) << name;
    EXPECT_EQ(run("mc --study nope").status, 2);
}

// --chains, --bootstrap, --large-step-probability, --camera-step-probability and --sigma
// override the scene's Metropolis parameters and reach the chains: the statistics report the
// chains and bootstrap samples used, a large-step probability of 1 leaves no small step, and
// sigma and the camera steps change the image.
TEST_F(Cli, MetropolisOptions) {
    const std::string scene = write("s.pbrt", kSmallScene);
    const std::string base = "render --quiet --integrator pssmlt --spp 2 --seed 3 " + scene;
    auto stats = [&](const std::string& opts, const std::string& name) {
        fs::path json = dir / (name + ".json");
        Result r = run(base + " " + opts + " -o " + (dir / (name + ".pfm")).string() + " --stats " + json.string());
        EXPECT_EQ(r.status, 0) << opts << "\n" << r.out;
        return nlohmann::json::parse(std::ifstream(json))["metropolis"];
    };
    nlohmann::json m =
        stats("--chains 7 --bootstrap 300 --large-step-probability 1 --sigma 0.05 --camera-step-probability 0.25", "a");
    EXPECT_NEAR(m["camera_step_probability"].get<double>(), 0.25, 1e-7);
    EXPECT_EQ(m["chains"], 7);
    EXPECT_EQ(m["bootstrap_samples"], 300);
    EXPECT_DOUBLE_EQ(m["large_step_probability"].get<double>(), 1.0);
    EXPECT_NEAR(m["sigma"].get<double>(), 0.05, 1e-7);
    EXPECT_EQ(m["small_steps"], 0);
    EXPECT_GT(m["large_steps"].get<long long>(), 0);
    nlohmann::json d = stats("--chains 7 --bootstrap 300", "d");  // the scene's (default) step mix
    EXPECT_GT(d["small_steps"].get<long long>(), 0);
    stats("--chains 7 --bootstrap 300 --sigma 0.2", "s");
    EXPECT_NE(ps::readImage((dir / "d.pfm").string()).rgb, ps::readImage((dir / "s.pfm").string()).rgb);
    stats("--chains 7 --bootstrap 300 --camera-step-probability 0", "c");
    EXPECT_NE(ps::readImage((dir / "d.pfm").string()).rgb, ps::readImage((dir / "c.pfm").string()).rgb);

    // Out of range, not a whole number, or with an integrator that has no chains: exit 2 and
    // a message naming the option.
    for (const std::string bad : {"--chains 0", "--chains 2.5", "--bootstrap -1", "--large-step-probability 1.5",
                                  "--large-step-probability -0.1", "--sigma 0", "--sigma nan",
                                  "--camera-step-probability 2"}) {
        Result r = run(base + " " + bad + " -o " + (dir / "x.pfm").string());
        EXPECT_EQ(r.status, 2) << bad << "\n" << r.out;
        EXPECT_NE(r.out.find(bad.substr(0, bad.find(' '))), std::string::npos) << bad << "\n" << r.out;
    }
    Result wrong = run("render --quiet --integrator bdpt --chains 8 " + scene + " -o " + (dir / "x.pfm").string());
    EXPECT_EQ(wrong.status, 2);
    EXPECT_NE(wrong.out.find("--integrator pssmlt"), std::string::npos) << wrong.out;
}

// A pbrt-v4 scene asking for Integrator "mlt" renders (with pssmlt, until multiplexed MLT
// exists) and says so; "regularize" true is named as biased and ignored.
// pbrt-v4's "mlt" is our multiplexed MLT; the statistics carry the chain's figures, per path
// depth too.
TEST_F(Cli, PbrtMltIntegratorIsMultiplexedMLT) {
    std::string text = kSmallScene;
    text.insert(text.find("WorldBegin"), R"(Integrator "mlt" "integer bootstrapsamples" [ 300 ] "integer chains" [ 7 ]
    "integer mutationsperpixel" [ 2 ] "bool regularize" true "integer maxdepth" [ 3 ]
)");
    const std::string scene = write("mlt.pbrt", text);
    fs::path json = dir / "stats.json";
    Result r = run("render --quiet " + scene + " -o " + (dir / "m.pfm").string() + " --stats " + json.string());
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("\"regularize\" true makes the image biased"), std::string::npos) << r.out;
    nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j["integrator"], "mmlt");
    EXPECT_EQ(j["spp_target"], 2);
    EXPECT_EQ(j["metropolis"]["chains"], 7);
    // Per depth; a tenth of them (the default --strategy-pilot) learn the strategy choice and
    // how to split the rest among the depths.
    EXPECT_EQ(j["metropolis"]["pilot_samples"], 30 * 4);
    EXPECT_NEAR(j["metropolis"]["bootstrap_samples"].get<double>(), 270 * 4, 4);
    ASSERT_EQ(j["metropolis"]["depths"].size(), 4u);
    double share = 0, chosen = 0, samples = 0;
    for (const auto& d : j["metropolis"]["depths"]) {
        share += d["share"].get<double>();
        chosen += d["choice_probability"].get<double>();
        samples += d["bootstrap_samples"].get<double>();
        EXPECT_TRUE(d.contains("acceptance_rate"));
    }
    EXPECT_NEAR(share, 1.0, 1e-9);
    EXPECT_NEAR(chosen, 1.0, 1e-5);
    EXPECT_EQ(samples, j["metropolis"]["bootstrap_samples"].get<double>());
    // The command line overrides the scene's parameters.
    Result o = run("render --quiet --chains 5 --spp 1 " + scene + " -o " + (dir / "m.pfm").string() + " --stats " +
                   json.string());
    ASSERT_EQ(o.status, 0) << o.out;
    j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j["metropolis"]["chains"], 5);
    EXPECT_EQ(j["spp_target"], 1);
    EXPECT_EQ(j["metropolis"]["two_stage_samples"], 300);  // two-stage MLT by default: F = 1
    // Without a pilot every bootstrap sample is the bootstrap's, and each depth is chosen
    // equally often.
    Result u = run("render --quiet --strategy-pilot 0 --spp 1 " + scene + " -o " + (dir / "m.pfm").string() +
                   " --stats " + json.string());
    ASSERT_EQ(u.status, 0) << u.out;
    j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j["metropolis"]["pilot_samples"], 0);
    EXPECT_EQ(j["metropolis"]["bootstrap_samples"], 300 * 4);
    for (const auto& d : j["metropolis"]["depths"]) EXPECT_NEAR(d["choice_probability"].get<double>(), 0.25, 1e-6);
    // The pilot cannot take the whole bootstrap, and belongs to mmlt alone.
    Result whole = run("render --quiet --strategy-pilot 1 " + scene + " -o " + (dir / "m.pfm").string());
    EXPECT_NE(whole.status, 0);
    EXPECT_NE(whole.out.find("--strategy-pilot must be below 1"), std::string::npos) << whole.out;
    Result other = run("render --quiet --strategy-pilot 0.5 --integrator bdpt " + scene + " -o " +
                       (dir / "m.pfm").string());
    EXPECT_NE(other.status, 0);
    EXPECT_NE(other.out.find("needs --integrator mmlt"), std::string::npos) << other.out;
    // Two-stage MLT: its pilot image's samples, F times "bootstrapsamples"; the depths'
    // shares of the image still sum to 1 (each splat's luminance is B there, not 1).
    Result two = run("render --quiet --two-stage 0.5 --spp 1 " + scene + " -o " + (dir / "m.pfm").string() +
                     " --stats " + json.string());
    ASSERT_EQ(two.status, 0) << two.out;
    j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j["metropolis"]["two_stage_samples"], 150);
    share = 0;
    for (const auto& d : j["metropolis"]["depths"]) share += d["share"].get<double>();
    EXPECT_NEAR(share, 1.0, 1e-9);
    Result notChains = run("render --quiet --two-stage 0.5 --integrator path " + scene + " -o " +
                           (dir / "m.pfm").string());
    EXPECT_NE(notChains.status, 0);
    EXPECT_NE(notChains.out.find("--two-stage-black-level are Metropolis parameters"), std::string::npos) << notChains.out;
    // --two-stage 0: the plain target, no pilot; a black level then has nothing to act on.
    Result plain = run("render --quiet --two-stage 0 --spp 1 " + scene + " -o " + (dir / "m.pfm").string() +
                       " --stats " + json.string());
    ASSERT_EQ(plain.status, 0) << plain.out;
    j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j["metropolis"]["two_stage_samples"], 0);
    Result level = run("render --quiet --two-stage 0 --two-stage-black-level 0.5 " + scene + " -o " +
                       (dir / "m.pfm").string());
    EXPECT_NE(level.status, 0);
    EXPECT_NE(level.out.find("--two-stage-black-level needs two-stage MLT"), std::string::npos) << level.out;
}

// --color spectral: every integrator renders it (path tracing, light tracing, BDPT, pssmlt, mmlt
// and Veach's mlt), and an unknown colour mode is refused.
TEST_F(Cli, SpectralColorRendersWithEveryIntegrator) {
    std::string scene = write("s.pbrt", kSmallScene);
    const std::string stats = (dir / "spectral.json").string();
    Result ok = run("render --quiet --color spectral --spp 4 " + scene + " --stats " + stats + " -o " + (dir / "p.exr").string());
    ASSERT_EQ(ok.status, 0) << ok.out;
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(stats))["color"].get<std::string>(), "spectral");
    for (const char* integrator : {"light", "bdpt", "pssmlt", "mmlt", "mlt"}) {
        const std::string out = (dir / (std::string(integrator) + ".exr")).string();
        Result r = run("render --quiet --color spectral --spp 4 --integrator " + std::string(integrator) + " " + scene +
                       " -o " + out);
        EXPECT_EQ(r.status, 0) << integrator << "\n" << r.out;
        EXPECT_TRUE(fs::exists(out)) << integrator;
    }
    EXPECT_EQ(run("render --quiet --color cmyk " + scene).status, 2);
}
