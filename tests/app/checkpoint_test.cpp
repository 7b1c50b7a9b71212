// Checkpoints (--checkpoint, --resume): a render stopped after a checkpoint and resumed gives
// the uninterrupted render's image bit for bit, on one process or several; a checkpoint that
// is damaged or of another render is refused, and nothing is overwritten.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "image/image.h"
#include "run_mpi.h"
#include "sky_scene.h"

namespace fs = std::filesystem;
using namespace ps::test;

namespace {

class Checkpoint : public SkyRenderTest {
protected:
    // A render of kSkyScene to NAME.pfm and NAME.json with `options`; its exit status and output.
    Result render(const std::string& name, const std::string& options, int processes = 0) {
        const std::string args = "render --quiet " + scene() + " " + options + " -o " + path(name + ".pfm") +
                                 " --stats " + path(name + ".json");
        return processes == 0 ? runPathspace(args) : runMpi(processes, args);
    }
};

}  // namespace

// SIGINT once a checkpoint exists (one after every pass): the image so far is written and
// normalised; resumed with other thread counts, and over 2 processes under mpirun, the
// path tracer's image equals the uninterrupted render's bit for bit.
TEST_F(Checkpoint, InterruptedAndResumedEqualsUninterrupted) {
    const std::string spp = "16384";
    ASSERT_EQ(render("full", "--threads 2 --spp " + spp).status, 0);

    {
        RunningPathspace p({"render", "--quiet", "--threads", "1", "--spp", spp, scene(), "-o", path("part.pfm"), "--stats",
                            path("part.json"), "--checkpoint", path("ck"), "--checkpoint-every", "0"});
        ASSERT_TRUE(p.waitUntilRendering(0.02)) << "pathspace exited or hung before rendering";
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
        while (!fs::exists(path("ck")) && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        ASSERT_TRUE(fs::exists(path("ck"))) << "no checkpoint written";
        // Enough samples after it for the interrupted image to resolve a 2% error (the
        // sanitizer build renders several times slower between checkpoints).
        ASSERT_TRUE(p.waitUntilRendering(cpuSeconds(0.3))) << "pathspace exited before the signal";
        EXPECT_TRUE(p.signalAndWaitTaken(SIGINT));
        ASSERT_EQ(p.wait(), 130);
    }
    nlohmann::json part = stats("part.json");
    EXPECT_TRUE(part["interrupted"].get<bool>());
    EXPECT_GE(part["checkpoints"].get<int>(), 1);
    expectExactSkyImage(ps::readImage(path("part.pfm")), "interrupted after a checkpoint");
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
        EXPECT_NE(e.path().filename().string().rfind("ck.tmp", 0), 0u) << "the temporary file was left behind";

    ASSERT_EQ(render("resumed", "--threads 2 --spp " + spp + " --resume " + path("ck")).status, 0);
    nlohmann::json r = stats("resumed.json");
    const int from = r["resumed_spp"].get<int>();
    std::printf("interrupted at %.0f spp (%d checkpoints); resumed from %d of %s spp\n", part["spp_mean"].get<double>(),
                part["checkpoints"].get<int>(), from, spp.c_str());
    EXPECT_GT(from, 0);
    EXPECT_LT(from, std::stoi(spp)) << "the render was not interrupted before its end";
    EXPECT_EQ(r["spp_mean"].get<double>(), std::stod(spp));
    EXPECT_EQ(r["camera_paths"], stats("full.json")["camera_paths"]);
    EXPECT_TRUE(bytes(path("resumed.pfm")) == bytes(path("full.pfm"))) << "resumed image differs from the uninterrupted one";

    std::string why;
    if (mpirunPath(why).empty()) {
        std::printf("resume over 2 processes not tested: %s\n", why.c_str());
        return;
    }
    ASSERT_EQ(render("resumed2", "--threads 1 --spp " + spp + " --resume " + path("ck"), 2).status, 0);
    EXPECT_EQ(stats("resumed2.json")["ranks"], 2);
    EXPECT_TRUE(bytes(path("resumed2.pfm")) == bytes(path("full.pfm")))
        << "resumed over 2 processes, the image differs from the uninterrupted one";
}

// Each bad checkpoint is refused with a message naming the file and the fault, exit status 2,
// and neither the output image nor the checkpoint (also named by --checkpoint) is touched.
TEST_F(Checkpoint, RefusesDamagedOrMismatchedCheckpoints) {
    ASSERT_EQ(render("make", "--threads 2 --spp 40 --checkpoint " + path("ck") + " --checkpoint-every 0").status, 0);
    const std::string good = bytes(path("ck"));
    ASSERT_GT(good.size(), 32u * 24 * 160);  // the film's sums
    std::ofstream(path("truncated"), std::ios::binary) << good.substr(0, good.size() / 2);
    std::string corrupt = good;
    corrupt[good.size() - 1000] ^= 0x10;  // one bit of the sums
    std::ofstream(path("corrupt"), std::ios::binary) << corrupt;
    write("other.pbrt", std::string(kSkyScene).replace(std::string(kSkyScene).find("0.5 0.5 0.5"), 11, "0.6 0.5 0.5"));

    struct Case {
        std::string what, file, options, message;
    };
    for (const Case& c : std::vector<Case>{
             {"truncated", "truncated", "--spp 40", "truncated or damaged"},
             {"corrupt", "corrupt", "--spp 40", "corrupt (its checksum does not match"},
             {"other scene", "ck", "--spp 40 --scene-file other.pbrt", "scene_file_hash"},
             {"lower spp", "ck", "--spp 39", "made for --spp 40: a resume may raise --spp, not lower it"},
             {"other integrator", "ck", "--spp 40 --integrator light", "integrator \"light\" here, \"path\" in the checkpoint"},
             {"not a checkpoint", "s.pbrt", "--spp 40", "not a pathspace checkpoint"}}) {
        SCOPED_TRACE(c.what);
        std::ofstream(path("out.pfm")) << "keep";
        std::string sceneFile = scene(), options = c.options;
        if (const size_t at = options.find(" --scene-file "); at != std::string::npos) {
            sceneFile = path(options.substr(at + 14));
            options = options.substr(0, at);
        }
        const Result r = runPathspace("render --quiet " + sceneFile + " " + options + " -o " + path("out.pfm") +
                                      " --resume " + path(c.file) + " --checkpoint " + path(c.file));
        EXPECT_EQ(r.status, 2) << r.out;
        EXPECT_NE(r.out.find("--resume \"" + path(c.file) + "\""), std::string::npos) << r.out;
        EXPECT_NE(r.out.find(c.message), std::string::npos) << r.out;
        EXPECT_TRUE(bytes(path("out.pfm")) == "keep") << "the output was overwritten";
        std::printf("%s: %s", c.what.c_str(), r.out.c_str());
    }
    EXPECT_TRUE(bytes(path("ck")) == good) << "the checkpoint was overwritten";
}

// A finished render's last checkpoint, resumed with --spp raised (twice: 16 -> 32 -> 64, the
// first raise over 2 processes when mpirun is here): the new samples come from sample sets of
// their own (RenderOptions::sampleSets), each a stratified set of its size. The image is
// right (the sky's exact values within 4 sigma), and its squared error is what three
// independent sets give: (16 A + 16 B + 32 C) / 64 has the variance e16 / 16 + e16 / 16 +
// e32 / 4, from the errors e16, e32 of renders of one set. (A second set that re-used the
// first one's points, B = A, would give e16 / 4 + e32 / 4, 1.7 times more here.) The sums of
// squares over ~600 pixels are good to about 10%.
TEST_F(Checkpoint, ResumeRaisesSpp) {
    // Each pixel's squared error against the exact image, summed.
    auto squaredError = [&](const std::string& name) {
        const ps::Image img = ps::readImage(path(name + ".pfm"));
        double e = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const ps::Spectrum v = img.get(x, y);
                const double d = (double(v.r) + v.g + v.b) / 3 - exactSkyPixel(x, y);
                if (std::isfinite(d)) e += d * d;  // the silhouette's pixels have no exact value
            }
        return e;
    };
    ASSERT_EQ(render("s16", "--sampler sobol --threads 2 --spp 16 --checkpoint " + path("ck")).status, 0);
    // Without --stats, which renders a QMC sampler's spp as scrambled sets (docs/strategy-figures.md).
    ASSERT_EQ(runPathspace("render --quiet " + scene() + " --sampler sobol --threads 2 --spp 32 --seed 7 -o " +
                           path("s32.pfm")).status,
              0);
    std::string why;
    const int processes = mpirunPath(why).empty() ? 0 : 2;
    ASSERT_EQ(render("r32", "--sampler sobol --threads 1 --spp 32 --resume " + path("ck") + " --checkpoint " + path("ck"), processes).status,
              0);
    const Result r = runPathspace("render " + scene() + " --sampler sobol --threads 2 --spp 64 --resume " + path("ck") + " -o " +
                                  path("r64.pfm") + " --stats " + path("r64.json"));
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("resumed from " + path("ck") + " at 32 spp; --spp raised from its 32 to 64"), std::string::npos)
        << r.out;
    EXPECT_EQ(stats("r32.json")["spp_mean"].get<double>(), 32);
    EXPECT_EQ(stats("r64.json")["spp_mean"].get<double>(), 64);
    EXPECT_EQ(stats("r64.json")["resumed_spp"].get<int>(), 32);
    expectExactSkyImage(ps::readImage(path("r64.pfm")), "16 spp raised to 32, then to 64");
    const double e16 = squaredError("s16"), e32 = squaredError("s32"), raised = squaredError("r64");
    const double independent = e16 / 8 + e32 / 4;
    std::printf("squared error: 16 spp %.4g, 32 spp %.4g, 16 -> 32 -> 64 spp %.4g (independent sets: %.4g)\n", e16,
                e32, raised, independent);
    EXPECT_GT(raised, 0.7 * independent);
    EXPECT_LT(raised, 1.4 * independent);
}

// Adaptive sampling does not checkpoint yet, and says so (Metropolis renders do:
// metropolis_checkpoint_test.cpp).
TEST_F(Checkpoint, RefusedWhereNotSupported) {
    for (const std::string opts : {"--adaptive twostage", "--adaptive sequential"}) {
        SCOPED_TRACE(opts);
        const Result r = render("x", "--spp 4 " + opts + " --checkpoint " + path("ck"));
        EXPECT_EQ(r.status, 2) << r.out;
        EXPECT_NE(r.out.find("does not yet write or resume checkpoints"), std::string::npos) << r.out;
        EXPECT_FALSE(fs::exists(path("ck")));
    }
}

// A render with --checkpoint stopped early (SIGINT, SIGTERM, --time; one process, or SIGINT to
// one of 2 processes) writes a last checkpoint at once, --checkpoint-every notwithstanding, of
// everything taken so far, the samples of the pass it stopped in included: resumed, the image
// is the uninterrupted render's bit for bit, and the two runs together took exactly the
// uninterrupted render's samples (none lost, none taken twice).
TEST_F(Checkpoint, StoppedEarlyWritesALastCheckpoint) {
    const std::string spp = "4096";
    ASSERT_EQ(render("full", "--threads 2 --spp " + spp).status, 0);
    const long long fullSamples = stats("full.json")["camera_paths"].get<long long>();
    std::string noMpi;
    mpirunPath(noMpi);
    for (const std::string how : {"SIGINT", "SIGTERM", "--time", "SIGINT to one of 2 processes"}) {
        SCOPED_TRACE(how);
        fs::remove(path("ck"));
        const std::vector<std::string> args{"render", "--quiet", "--threads", "1", "--spp", spp, scene(), "-o",
                                            path("part.pfm"), "--stats", path("part.json"), "--checkpoint", path("ck"),
                                            "--checkpoint-every", "1000"};
        if (how == "--time") {
            std::vector<std::string> a = args;
            a.insert(a.end(), {"--time", "0.1"});
            std::string line;
            for (const std::string& s : a) line += s + " ";
            ASSERT_EQ(runPathspace(line).status, 0);
        } else if (how == "SIGINT to one of 2 processes") {
            if (!noMpi.empty()) {
                std::printf("%s: not tested, %s\n", how.c_str(), noMpi.c_str());
                continue;
            }
            RunningMpiJob job(2, args);
            ASSERT_TRUE(job.waitUntilRendering(cpuSeconds(0.05))) << "the job ended or hung before rendering";
            kill(job.ranks().back(), SIGINT);
            ASSERT_EQ(job.wait(), 130);
        } else {
            RunningPathspace p(args);
            ASSERT_TRUE(p.waitUntilRendering(cpuSeconds(0.05))) << "pathspace exited or hung before rendering";
            EXPECT_TRUE(p.signalAndWaitTaken(how == "SIGINT" ? SIGINT : SIGTERM));
            ASSERT_EQ(p.wait(), 130);
        }
        nlohmann::json part = stats("part.json");
        EXPECT_TRUE(part["stopped_early"].get<bool>()) << "the render was not stopped before its end";
        EXPECT_EQ(part["checkpoints"], 1) << "no last checkpoint counted";
        ASSERT_TRUE(fs::exists(path("ck"))) << "no last checkpoint written";

        ASSERT_EQ(render("resumed", "--threads 2 --spp " + spp + " --resume " + path("ck")).status, 0);
        nlohmann::json r = stats("resumed.json");
        const long long before = part["camera_paths"].get<long long>(), after = r["rank_samples"][0].get<long long>();
        std::printf("%s: stopped at %.2f spp, resumed from %d spp + a part of the next pass; samples %lld + %lld = %lld "
                    "(uninterrupted %lld)\n",
                    how.c_str(), part["spp_mean"].get<double>(), r["resumed_spp"].get<int>(), before, after,
                    before + after, fullSamples);
        EXPECT_EQ(before + after, fullSamples) << "samples lost or taken twice";
        EXPECT_EQ(r["camera_paths"].get<long long>(), fullSamples);
        EXPECT_TRUE(bytes(path("resumed.pfm")) == bytes(path("full.pfm")))
            << "the image resumed from the last checkpoint differs from the uninterrupted one";
    }
}

// The checkpoint covers every file the scene reads, not only the scene file: when an
// included scene file or a PLY mesh has changed since, --resume refuses, naming that file,
// and nothing is written; with the files as they were, it resumes.
TEST_F(Checkpoint, RefusesWhenAFileTheSceneReadsChanged) {
    std::string main = kSkyScene;
    main.replace(main.find("Material"), std::string::npos, "Include \"sub/object.pbrt\"\n");
    write("main.pbrt", main);
    fs::create_directories(dir / "sub");
    const std::string object = "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
                               "Shape \"sphere\" \"float radius\" [ 1 ]\n"
                               "Shape \"plymesh\" \"string filename\" \"sub/quad.ply\"\n";
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "-2 -2 -1\n2 -2 -1\n0 2 -1\n3 0 1 2\n";
    write("sub/object.pbrt", object);
    write("sub/quad.ply", ply);
    const std::string run = "render --quiet " + path("main.pbrt") + " --spp 8 -o " + path("out.pfm");
    ASSERT_EQ(runPathspace(run + " --checkpoint " + path("ck") + " --checkpoint-every 0").status, 0);

    struct Case {
        std::string what, file, text;
    };
    auto replaced = [](std::string text, const std::string& a, const std::string& b) {
        return text.replace(text.find(a), a.size(), b);
    };
    for (const Case& c : std::vector<Case>{{"included scene file", "sub/object.pbrt", replaced(object, "0.5 0.5 0.5", "0.6 0.5 0.5")},
                                           {"PLY mesh", "sub/quad.ply", replaced(ply, "0 2 -1", "0 3 -1")}}) {
        SCOPED_TRACE(c.what);
        const std::string before = bytes(path(c.file));
        ASSERT_NE(c.text, before);
        write(c.file, c.text);
        std::ofstream(path("out.pfm")) << "keep";
        const Result r = runPathspace(run + " --resume " + path("ck"));
        EXPECT_EQ(r.status, 2) << r.out;
        EXPECT_NE(r.out.find("\"" + c.file + "\" has changed since the checkpoint"), std::string::npos) << r.out;
        EXPECT_TRUE(bytes(path("out.pfm")) == "keep") << "the output was overwritten";
        std::printf("%s changed: %s", c.what.c_str(), r.out.c_str());
        write(c.file, before);
    }
    const Result same = runPathspace(run + " --resume " + path("ck"));
    EXPECT_EQ(same.status, 0) << "with the files as they were: " << same.out;
}
