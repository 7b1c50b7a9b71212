// Renders over K processes (mpirun -n K, on this machine over loopback): each process takes a
// share of every pixel's sample indices and the film's exact sums are added on rank 0, so the
// image is the one process's, bit for bit, for any K and thread count; time limits and
// signals stop every process together and the image is normalised by the samples taken.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "film/film.h"
#include "image/image.h"
#include "furnace_scene.h"
#include "run_mpi.h"
#include "sky_scene.h"

namespace fs = std::filesystem;
using namespace ps::test;

namespace {

class Mpi : public SkyRenderTest {
protected:
    // Renders with `options` to NAME.pfm (and its variance AOV) and NAME.json, by one plain
    // process (processes == 0) or under mpirun; expects success.
    void render(int processes, const std::string& name, const std::string& options) {
        std::string args = "render --quiet " + scene() + " " + options + " --aov variance -o " + path(name + ".pfm") +
                           " --stats " + path(name + ".json");
        Result r = processes == 0 ? runPathspace(args) : runMpi(processes, args);
        ASSERT_EQ(r.status, 0) << r.out;
    }
    // NAME.pfm and its variance image have the bits of REF's.
    void expectSameBits(const std::string& name, const std::string& ref) {
        for (const char* suffix : {".pfm", ".variance.pfm"}) {
            std::string a = bytes(path(ref + suffix)), b = bytes(path(name + suffix));
            ASSERT_FALSE(a.empty());
            EXPECT_TRUE(a == b) << name << suffix << " differs from " << ref << suffix;
        }
    }
};

// `mpirun -n 1 pathspace ARGS0 : -n 1 pathspace ARGS1`: rank 0 and rank 1 started with
// different arguments (Open MPI's several-programs form), so that one process alone meets
// what the other does not, as processes on different machines may.
Result runTwoDifferentProcesses(const std::string& args0, const std::string& args1) {
    std::string cmd;
    for (const std::string& a : mpirunArgs(1)) cmd += a + " ";
    return runCommand(cmd + args0 + " : -n 1 " + PATHSPACE_BINARY + " " + args1);
}

int occurrences(const std::string& text, const std::string& what) {
    int n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace

// The path tracer (Sobol sampler, the default) over 1, 2 and 4 processes with 1 or 2 threads
// each: the image and the variance image of one process with 2 threads, bit for bit; the
// statistics count every sample once and name each process's share.
TEST_F(Mpi, PathTracerImageIndependentOfProcessesAndThreads) {
    PS_SKIP_WITHOUT_MPI();
    const std::string opts = "--spp 23 --sampler sobol --integrator path";
    render(0, "plain", opts + " --threads 2");
    const long long samples = 32 * 24 * 23;
    EXPECT_EQ(stats("plain.json")["ranks"], 1);
    for (auto [k, threads] : {std::pair{1, 1}, {2, 2}, {2, 1}, {4, 1}}) {
        const std::string name = "k" + std::to_string(k) + "t" + std::to_string(threads);
        SCOPED_TRACE(name);
        render(k, name, opts + " --threads " + std::to_string(threads));
        expectSameBits(name, "plain");
        nlohmann::json j = stats(name + ".json");
        EXPECT_EQ(j["ranks"], k);
        ASSERT_EQ(j["rank_samples"].size(), size_t(k));
        ASSERT_EQ(j["rank_seconds"].size(), size_t(k));
        long long sum = 0;
        for (const auto& n : j["rank_samples"]) {
            sum += n.get<long long>();
            EXPECT_NEAR(n.get<double>(), double(samples) / k, 0.02 * samples / k) << "an uneven share";
        }
        EXPECT_EQ(sum, samples);
        EXPECT_EQ(j["camera_paths"], stats("plain.json")["camera_paths"]);
        EXPECT_EQ(j["spp_mean"].get<double>(), 23.0);
        if (k > 1) {
            EXPECT_GT(j["reduction_bytes"].get<double>(), 32 * 24 * 160.0);  // the film's sums
            EXPECT_GT(j["reduction_seconds"].get<double>(), 0.0);
        }
    }
}

// Two-stage adaptive sampling over 2 and 3 processes: the pilot's exact sums are added on
// rank 0, which allocates the second stage and sends the allocation to the others; every
// process takes its share of both stages, so the image, its variance and the per-pixel counts
// (hence the statistics) are one process's bit for bit. Also under --time (a sample budget
// from the rate measured on rank 0, the same on every process): the exact image within 4 sigma.
TEST_F(Mpi, TwoStageAdaptiveSamplingImageIndependentOfProcesses) {
    PS_SKIP_WITHOUT_MPI();
    const std::string opts = "--spp 64 --adaptive twostage --integrator path";
    render(0, "plain", opts + " --threads 2");
    for (int k : {2, 3}) {
        const std::string name = "k" + std::to_string(k);
        SCOPED_TRACE(name);
        render(k, name, opts + " --threads 1");
        expectSameBits(name, "plain");
        nlohmann::json j = stats(name + ".json"), plain = stats("plain.json");
        EXPECT_EQ(j["ranks"], k);
        EXPECT_EQ(j["camera_paths"], plain["camera_paths"]);
        EXPECT_EQ(j["spp_mean"], plain["spp_mean"]);
        for (const auto& n : j["rank_samples"])
            EXPECT_NEAR(n.get<double>(), plain["camera_paths"].get<double>() / k, 0.02 * plain["camera_paths"].get<double>() / k)
                << "an uneven share";
        std::printf("%d processes: samples %s of %s\n", k, j["rank_samples"].dump().c_str(),
                    plain["camera_paths"].dump().c_str());
    }
    render(2, "timed", "--spp 100000000 --adaptive twostage --threads 1 --time 0.6");
    expectExactSkyImage(ps::readImage(path("timed.pfm")), "two-stage, --time, 2 processes");
    // The budget, turned into samples from the measured rate, ends the render near its time.
    nlohmann::json t = stats("timed.json");
    EXPECT_LT(t["spp_mean"].get<double>(), 1e8);
    for (const auto& sec : t["rank_seconds"]) EXPECT_LT(sec.get<double>(), 5.0);
    for (const auto& n : t["rank_samples"]) EXPECT_GT(n.get<long long>(), 32 * 24 * 8);
}

// Light tracing and BDPT splat onto the whole film, in fixed point: the same bits too.
TEST_F(Mpi, SplattingIntegratorsImageIndependentOfProcesses) {
    PS_SKIP_WITHOUT_MPI();
    for (const std::string integrator : {"light", "bdpt"}) {
        SCOPED_TRACE(integrator);
        const std::string opts = "--spp 9 --integrator " + integrator;
        render(0, integrator, opts + " --threads 1");
        for (int k : {2, 4}) {
            const std::string name = integrator + std::to_string(k);
            render(k, name, opts + " --threads 2");
            expectSameBits(name, integrator);
            EXPECT_EQ(stats(name + ".json")["light_paths"], stats(integrator + ".json")["light_paths"]);
        }
    }
}

// --time over 2 processes: both stop, together, and the image is normalised by the samples
// each pixel received (kSkyScene's exact image within 4 sigma).
TEST_F(Mpi, TimeLimitStopsEveryProcess) {
    PS_SKIP_WITHOUT_MPI();
    render(2, "t", "--spp 100000000 --threads 1 --time 0.6");
    expectExactSkyImage(ps::readImage(path("t.pfm")), "--time, 2 processes");
    nlohmann::json j = stats("t.json");
    EXPECT_TRUE(j["stopped_early"].get<bool>());
    EXPECT_FALSE(j["interrupted"].get<bool>());
    for (const auto& s : j["rank_seconds"]) EXPECT_LT(s.get<double>(), 5.0);
    for (const auto& n : j["rank_samples"]) EXPECT_GT(n.get<long long>(), 32 * 24 * 8);
}

// Ctrl-C to mpirun (which passes SIGTERM to every process) and SIGINT to one process only:
// every process stops at the same pass boundary, rank 0 writes the normalised image, and the
// statistics say interrupted.
TEST_F(Mpi, SignalStopsEveryProcess) {
    PS_SKIP_WITHOUT_MPI();
    for (bool launcher : {true, false}) {
        SCOPED_TRACE(launcher ? "SIGINT to mpirun" : "SIGINT to one process");
        fs::remove(path("i.pfm"));
        fs::remove(path("i.json"));
        {
            RunningMpiJob job(2, {"render", "--quiet", "--spp", "100000000", "--threads", "1", scene(), "-o",
                                  path("i.pfm"), "--stats", path("i.json")});
            ASSERT_TRUE(job.waitUntilRendering(0.3)) << "the job ended or hung before rendering";
            if (launcher) job.signalLauncher(SIGINT);
            else kill(job.ranks().back(), SIGINT);
            const int status = job.wait();
            // mpirun ends with 1 when it was signalled, else with the processes' 130.
            EXPECT_EQ(status, launcher ? 1 : 130);
        }
        ASSERT_TRUE(fs::exists(path("i.pfm"))) << "no image written";
        expectExactSkyImage(ps::readImage(path("i.pfm")), launcher ? "SIGINT to mpirun" : "SIGINT to one process");
        nlohmann::json j = stats("i.json");
        EXPECT_TRUE(j["interrupted"].get<bool>());
        EXPECT_EQ(j["ranks"], 2);
    }
}

// Sequential adaptive sampling over 2 and 3 processes: every round's pixels are chosen on
// rank 0 from the summed films (one process's film, exactly) and sent to the others, so the
// image, its variance and the statistics are one process's bit for bit.
TEST_F(Mpi, SequentialAdaptiveSamplingImageIndependentOfProcesses) {
    PS_SKIP_WITHOUT_MPI();
    const std::string opts = "--spp 32 --adaptive sequential --integrator path";
    render(0, "plain", opts + " --threads 2");
    for (int k : {2, 3}) {
        const std::string name = "k" + std::to_string(k);
        SCOPED_TRACE(name);
        render(k, name, opts + " --threads 1");
        expectSameBits(name, "plain");
        EXPECT_EQ(stats(name + ".json")["camera_paths"], stats("plain.json")["camera_paths"]);
        EXPECT_EQ(stats(name + ".json")["ranks"], k);
    }
}

// --bdpt-strategies over 2 processes: the per-strategy images (their sums in the film's fixed
// point, summed on rank 0) are one process's bit for bit, as is the image.
TEST_F(Mpi, BdptStrategyImagesIndependentOfProcesses) {
    PS_SKIP_WITHOUT_MPI();
    const std::string opts = "--spp 6 --integrator bdpt --maxdepth 3 --bdpt-strategies ";
    render(0, "plain", opts + path("st1") + " --threads 2");
    render(2, "k2", opts + path("st2") + " --threads 1");
    expectSameBits("k2", "plain");
    int images = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(path("st1"))) {
        const std::string name = e.path().filename().string();
        EXPECT_TRUE(bytes(e.path().string()) == bytes(path("st2/" + name))) << name << " differs over 2 processes";
        ++images;
    }
    EXPECT_EQ(images, 26);  // depths 0..3: 14 camera strategies and 3 light-tracing ones, weighted and not
}

namespace {

// The mean over the image of the pixels' channel means.
double imageMean(const ps::Image& img) {
    double s = 0;
    for (float v : img.rgb) s += v;
    return s / double(img.rgb.size());
}

}  // namespace

// Metropolis over 1 and 2 processes (chains split by index, one shared bootstrap, the splat
// films' fixed-point sums added on rank 0, the image normalised by every process's
// mutations): pssmlt and mmlt on kSkyScene, Veach's mlt on a furnace, each the image and the
// (half-buffer) variance of one process bit for bit, with the same b and chain statistics,
// and the statistics name each process's mutations and acceptance.
TEST_F(Mpi, MetropolisImageIndependentOfProcesses) {
    PS_SKIP_WITHOUT_MPI();
    const std::string furnace = write("furnace.pbrt", kFurnace);
    // Two-stage MLT's pilot image too, its blocks split among the processes.
    for (const std::string configuration : {"pssmlt", "mmlt", "mlt", "mmlt --two-stage 0.5"}) {
        SCOPED_TRACE(configuration);
        const std::string integrator = configuration == "mmlt --two-stage 0.5" ? "mmlt-two-stage" : configuration;
        auto run = [&](int k, const std::string& name, int threads) {
            std::string args = "render --quiet " + (integrator == "mlt" ? furnace : scene()) + " --spp 8 --bootstrap 3000 "
                               "--chains 13 --integrator " + configuration + " --threads " + std::to_string(threads) +
                               " --aov variance -o " + path(name + ".pfm") + " --stats " + path(name + ".json");
            Result r = k == 0 ? runPathspace(args) : runMpi(k, args);
            ASSERT_EQ(r.status, 0) << r.out;
        };
        run(0, integrator, 2);
        const nlohmann::json plain = stats(integrator + ".json")["metropolis"];
        for (int k : {1, 2}) {
            const std::string name = integrator + std::to_string(k);
            SCOPED_TRACE(name);
            run(k, name, 1);
            expectSameBits(name, integrator);
            const nlohmann::json j = stats(name + ".json"), m = j["metropolis"];
            EXPECT_EQ(j["ranks"], k);
            EXPECT_EQ(m["b"], plain["b"]);
            EXPECT_EQ(m["mutations"], plain["mutations"]);
            EXPECT_EQ(m["acceptance_rate"], plain["acceptance_rate"]);
            EXPECT_EQ(j["rays"], stats(integrator + ".json")["rays"]);
            ASSERT_EQ(m["rank_mutations"].size(), size_t(k));
            ASSERT_EQ(m["rank_acceptance_rates"].size(), size_t(k));
            long long sum = 0;
            for (const auto& n : m["rank_mutations"]) {
                sum += n.get<long long>();
                EXPECT_GT(n.get<long long>(), 0);
            }
            EXPECT_EQ(sum, plain["mutations"].get<long long>());
            EXPECT_EQ(j["rank_samples"], m["rank_mutations"]);
            for (const auto& a : m["rank_acceptance_rates"]) EXPECT_GT(a.get<double>(), 0.0);
        }
    }
}

// A Metropolis render over 2 processes stopped early, by SIGINT to one process (pssmlt on
// kSkyScene) or by --time (mlt on the furnace): every process stops at the same pass of
// mutations and the image is normalised by all the mutations made (normalised by one
// process's it would be twice as bright). A chain's pixels are correlated, so the class means
// are held to 3% of the exact values, as for one process (interrupt_test.cpp).
TEST_F(Mpi, StoppedMetropolisIsNormalisedByEveryProcessMutations) {
    PS_SKIP_WITHOUT_MPI();
    // CPU seconds one process takes to load, bootstrap and start the chains (the bootstrap is
    // fixed work, much longer under the sanitizers); split over 2, each takes less.
    const auto start = std::chrono::steady_clock::now();
    render(0, "start", "--spp 1 --integrator pssmlt --bootstrap 20000 --chains 64 --threads 1");
    const double startSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    {
        RunningMpiJob job(2, {"render", "--quiet", "--spp", "100000000", "--threads", "1", "--integrator", "pssmlt",
                              "--bootstrap", "20000", "--chains", "64", scene(), "-o", path("i.pfm"), "--stats",
                              path("i.json")});
        ASSERT_TRUE(job.waitUntilRendering(startSeconds + cpuSeconds(0.5))) << "the job ended or hung before rendering";
        kill(job.ranks().back(), SIGINT);
        EXPECT_EQ(job.wait(), 130);
    }
    ASSERT_TRUE(fs::exists(path("i.pfm"))) << "no image written";
    nlohmann::json j = stats("i.json"), m = j["metropolis"];
    EXPECT_TRUE(j["interrupted"].get<bool>());
    EXPECT_TRUE(j["stopped_early"].get<bool>());
    ASSERT_EQ(m["rank_mutations"].size(), 2u);
    const long long made = m["mutations"].get<long long>();
    EXPECT_EQ(m["rank_mutations"][0].get<long long>() + m["rank_mutations"][1].get<long long>(), made);
    EXPECT_GT(m["rank_mutations"][0].get<long long>(), 10000);
    EXPECT_GT(m["rank_mutations"][1].get<long long>(), 10000);
    double sphere = 0, sky = 0;
    int nSphere = 0, nSky = 0;
    const ps::Image img = ps::readImage(path("i.pfm"));
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const double exact = exactSkyPixel(x, y);
            if (std::isnan(exact)) continue;
            const ps::Spectrum v = img.get(x, y);
            (exact == 1.0 ? sky : sphere) += (double(v.r) + v.g + v.b) / 3;
            ++(exact == 1.0 ? nSky : nSphere);
        }
    sphere /= nSphere;
    sky /= nSky;
    std::printf("SIGINT to one of 2 processes: %lld mutations; sphere %.4f (exact 0.5), sky %.4f (exact 1)\n", made,
                sphere, sky);
    EXPECT_NEAR(sphere, 0.5, 0.015);
    EXPECT_NEAR(sky, 1.0, 0.03);

    const std::string furnace = write("furnace.pbrt", kFurnace);
    Result r = runMpi(2, "render --quiet " + furnace + " --integrator mlt --spp 100000000 --bootstrap 20000 --chains 64 "
                      "--threads 1 --time " + std::to_string(startSeconds + cpuSeconds(1.0)) + " -o " + path("t.pfm") +
                      " --stats " + path("t.json"));
    ASSERT_EQ(r.status, 0) << r.out;
    nlohmann::json t = stats("t.json");
    EXPECT_TRUE(t["stopped_early"].get<bool>());
    EXPECT_FALSE(t["interrupted"].get<bool>());
    for (const auto& n : t["metropolis"]["rank_mutations"]) EXPECT_GT(n.get<long long>(), 10000);
    const double mean = imageMean(ps::readImage(path("t.pfm")));
    std::printf("mlt, --time, 2 processes: %lld mutations; mean %.4f (exact %.4f)\n",
                t["metropolis"]["mutations"].get<long long>(), mean, kFurnaceValue);
    EXPECT_NEAR(mean, kFurnaceValue, 0.03 * kFurnaceValue);
}

// A process killed outright (SIGKILL: a crash, a lost node) ends the whole job with a failure
// status, and nothing hangs (the job has a 60 s watchdog, and must end well within it); the
// last checkpoint survives, and resumed on one process gives the uninterrupted image bit for
// bit (path tracer).
TEST_F(Mpi, KilledProcessEndsTheJobAndItsCheckpointResumes) {
    PS_SKIP_WITHOUT_MPI();
    const std::string spp = "8192";
    render(0, "full", "--threads 2 --spp " + spp);
    const std::string ck = path("ck");
    double secondsToEnd = 0;
    {
        RunningMpiJob job(2, {"render", "--quiet", "--threads", "1", "--spp", spp, scene(), "-o", path("killed.pfm"),
                              "--checkpoint", ck, "--checkpoint-every", "0"});
        ASSERT_TRUE(job.waitUntilRendering(0.01)) << "the job ended or hung before rendering";
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
        while (!fs::exists(ck) && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        ASSERT_TRUE(fs::exists(ck)) << "no checkpoint written";
        ASSERT_TRUE(job.waitUntilRendering(cpuSeconds(0.1))) << "the job ended before the kill";
        const auto killed = std::chrono::steady_clock::now();
        ASSERT_EQ(kill(job.ranks().back(), SIGKILL), 0);
        const int status = job.wait();
        secondsToEnd = std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
        std::printf("job status %d\n", status);
        EXPECT_NE(status, 0) << "the job succeeded with a process killed";
        EXPECT_NE(status, 124) << "the job hung until its watchdog (timeout 60) ended it";
        EXPECT_LT(secondsToEnd, 30.0);
    }
    EXPECT_FALSE(fs::exists(path("killed.pfm"))) << "an image was written by a job that lost a process";
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
        EXPECT_NE(e.path().filename().string().rfind("ck.tmp", 0), 0u) << "a temporary checkpoint was left behind";

    Result r = runPathspace("render --quiet " + scene() + " --threads 2 --spp " + spp + " --resume " + ck + " -o " +
                            path("resumed.pfm") + " --stats " + path("resumed.json"));
    ASSERT_EQ(r.status, 0) << r.out;
    const int from = stats("resumed.json")["resumed_spp"].get<int>();
    std::printf("job ended %.2f s after the kill; resumed on one process from %d of %s spp\n", secondsToEnd, from,
                spp.c_str());
    EXPECT_GT(from, 0);
    EXPECT_LT(from, std::stoi(spp));
    EXPECT_EQ(stats("resumed.json")["camera_paths"], stats("full.json")["camera_paths"]);
    EXPECT_TRUE(bytes(path("resumed.pfm")) == bytes(path("full.pfm")))
        << "resumed from the killed job's checkpoint, the image differs from the uninterrupted one";
}

// One voice per job: a warning that every process meets parsing the scene is printed once
// (by rank 0) and counted once; a refusal that a process meets during the render (mlt's
// smooth coating over a smooth conductor, met in the bootstrap by the process that takes
// its one block of samples) is raised by every process together: one message, exit status
// 2, no abort of the job and no hang.
TEST_F(Mpi, OneVoicePerJob) {
    PS_SKIP_WITHOUT_MPI();
    const std::string base = R"(LookAt 0 0.5 2  0 0.5 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ] "float bogus" [ 1 ]
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
  Shape "bilinearmesh" "point3 P" [ -0.2 1 -0.2   0.2 1 -0.2   -0.2 1 0.2   0.2 1 0.2 ]
AttributeEnd
)";
    const std::string warned = write("warned.pbrt", base + "Shape \"sphere\" \"float radius\" [ 0.2 ]\n");
    const Result w = runMpi(2, "render --quiet " + warned + " --spp 4 -o " + path("w.pfm") + " --stats " + path("w.json"));
    ASSERT_EQ(w.status, 0) << w.out;
    EXPECT_EQ(occurrences(w.out, "unused parameter \"float bogus\""), 1) << w.out;
    EXPECT_EQ(stats("w.json")["warnings"], 1);

    const std::string coated = write("coated.pbrt", base + "Material \"coatedconductor\"\nShape \"sphere\" \"float radius\" [ 0.2 ]\n");
    const auto start = std::chrono::steady_clock::now();
    const Result r = runMpi(2, "render --quiet " + coated + " --integrator mlt --spp 1 --bootstrap 256 --chains 4 -o " +
                                   path("c.pfm"));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("refused in %.2f s, status %d\n", seconds, r.status);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.status, 124) << "the job hung until its watchdog ended it";
    EXPECT_EQ(occurrences(r.out, "coatedconductor whose coating and conductor are both smooth"), 1) << r.out;
    EXPECT_EQ(occurrences(r.out, "rank 1"), 0) << r.out;
    EXPECT_EQ(occurrences(r.out, "MPI_ABORT"), 0) << r.out;
    EXPECT_FALSE(fs::exists(path("c.pfm")));
}

// An input error met before the render (a syntax error in the scene, a missing Include, a
// bad option on the command line) is every process's: rank 0 reports it once and every
// process ends with status 2, none aborting the job (mpirun prints no MPI_ABORT note, nor
// the error its help system logs when an abort cuts it short). Met by one process only (a
// file that process alone reads), it still aborts the job, rank 0 naming the failing rank.
TEST_F(Mpi, InputErrorBeforeTheRenderIsEveryProcesss) {
    PS_SKIP_WITHOUT_MPI();
    const std::string syntax =
        write("syntax.pbrt", "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                             "Shape \"sphere\" \"float radius\" [ 1 ] ]\n");
    const std::string include = write("include.pbrt", "WorldBegin\nInclude \"nothere.pbrt\"\n");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"render --quiet " + syntax + " -o " + path("a.pfm"), "syntax.pbrt:4:37: error: expected a directive"},
        {"render --quiet " + include + " -o " + path("a.pfm"), "include.pbrt:2:1: error: Include: cannot read the file"},
        {"render --quiet " + scene() + " --spp 0 -o " + path("a.pfm"), "--spp: expected a whole number >= 1"},
        {"render --quiet " + scene() + " --mlt-direct 1 -o " + path("a.pfm"), "--mlt-direct renders direct lighting"},
        {"render --quiet " + scene() + " -o " + path("a.txt"), "unsupported extension"},
    };
    for (const auto& [args, message] : cases) {
        const Result r = runMpi(2, args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
        EXPECT_EQ(occurrences(r.out, message), 1) << args << "\n" << r.out;
        EXPECT_EQ(occurrences(r.out, "rank 1"), 0) << r.out;
        EXPECT_EQ(occurrences(r.out, "MPI_ABORT"), 0) << args << "\n" << r.out;
        EXPECT_EQ(occurrences(r.out, "ORTE_ERROR_LOG"), 0) << args << "\n" << r.out;
    }
    EXPECT_FALSE(fs::exists(path("a.pfm")));

    const std::string good = "render --quiet " + scene() + " -o " + path("b.pfm");
    const Result r = runTwoDifferentProcesses(good, "render --quiet " + include + " -o " + path("b.pfm"));
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_EQ(occurrences(r.out, "rank 1: "), 1) << r.out;
    EXPECT_EQ(occurrences(r.out, "include.pbrt:2:1: error: Include: cannot read the file"), 1) << r.out;
    EXPECT_FALSE(fs::exists(path("b.pfm")));
}

// A warning that only rank 1 meets (its scene file, otherwise the same, has a parameter that
// no directive uses) reaches rank 0 after the render, which prints it once and counts it.
TEST_F(Mpi, WarningMetOnlyOffRankZeroIsPrintedOnce) {
    PS_SKIP_WITHOUT_MPI();
    std::string text = kSkyScene;
    const std::string plain = write("plain.pbrt", text);
    const size_t film = text.find("Film \"rgb\"");
    ASSERT_NE(film, std::string::npos);
    text.insert(film + 10, " \"float bogus\" [ 1 ]");
    const std::string bogus = write("bogus.pbrt", text);
    const std::string options = " --spp 4 -o " + path("w.pfm") + " --stats " + path("w.json");
    const Result r = runTwoDifferentProcesses("render --quiet " + plain + options, "render --quiet " + bogus + options);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(occurrences(r.out, "unused parameter \"float bogus\""), 1) << r.out;
    EXPECT_EQ(occurrences(r.out, "bogus.pbrt:"), 1) << r.out;
    EXPECT_EQ(stats("w.json")["warnings"], 1);
}

// reduction_bytes counts every collective of the render, by purpose, and each purpose what
// the code sends: for the path tracer on 2 processes, the film's reduction (each pixel's
// 128-bit sums and its count, the film's other count, the statistics gathered with them),
// a stop decision after each of the 4 passes and one after the render, the warnings' size,
// the decisions whether any process met an input error before the render;
// for pssmlt, the same splat film, every chain's counts and at least the bootstrap's weights
// and a film per checkpoint. The purposes add up to the total.
TEST_F(Mpi, ReductionBytesCountEveryTransfer) {
    PS_SKIP_WITHOUT_MPI();
    auto purposes = [&](const std::string& name) {
        const nlohmann::json j = stats(name);
        double sum = 0;
        std::map<std::string, double> by;
        for (const auto& [purpose, t] : j["reduction_by_purpose"].items()) {
            by[purpose] = t["bytes"].get<double>();
            sum += by[purpose];
            std::printf("%s: %s %.0f bytes\n", name.c_str(), purpose.c_str(), by[purpose]);
        }
        EXPECT_EQ(sum, j["reduction_bytes"].get<double>());
        return by;
    };
    constexpr double kPixelBytes = 16 * ps::Film::kPixelSums + 8, kStatistics = 7 * 8 + 2 * 8;
    render(2, "path", "--spp 8 --threads 1");  // passes of 1, 2, 4 and 1 samples
    const double pixels = 32 * 24;
    std::map<std::string, double> p = purposes("path.json");
    EXPECT_EQ(p["film"], pixels * kPixelBytes + 8 + kStatistics);
    EXPECT_EQ(p["stop decisions"], 4 * 4 + 4);
    EXPECT_EQ(p["warnings"], 8);
    // Whether any process met an input error: after the command line and the scene (two ints
    // each), and in rank 0's checks of its outputs (one).
    EXPECT_EQ(p["error decisions"], 2 * 8 + 4);
    EXPECT_EQ(p.size(), 4u);

    const std::string furnace = write("furnace.pbrt", kFurnace);
    const Result r = runMpi(2, "render --quiet " + furnace + " --integrator pssmlt --spp 64 --bootstrap 3000 --chains 13 "
                               "--threads 1 --checkpoint " + path("ck") + " --checkpoint-every 0 -o " + path("m.pfm") +
                               " --stats " + path("m.json"));
    ASSERT_EQ(r.status, 0) << r.out;
    const double splatPixels = 16 * 16, depths = 6, checkpoints = stats("m.json")["checkpoints"].get<double>();
    const double sums = splatPixels * kPixelBytes + (splatPixels * 6 + 1) * 8;  // a splat film's
    std::map<std::string, double> m = purposes("m.json");
    EXPECT_EQ(m["film"], sums + kStatistics);
    EXPECT_EQ(m["chain counts"], 13 * (6 + 3 * depths) * 8);
    EXPECT_GE(m["bootstrap merge"], 3000 * 8);
    EXPECT_EQ(checkpoints, 5);  // after each of the 5 passes, the last at the end
    EXPECT_GE(m["checkpoint"], checkpoints * sums);
}
