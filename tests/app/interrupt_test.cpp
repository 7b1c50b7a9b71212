// Early stops of the pathspace command: SIGINT, SIGTERM and --time write the image so far,
// each pixel normalised by the samples it received, so it must match the exact image of
// kSkyScene within noise; a second Ctrl-C leaves at once without writing anything.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include <sys/resource.h>
#include <vector>

#include "image/image.h"
#include "run_binary.h"
#include "sky_scene.h"

namespace fs = std::filesystem;
using namespace ps::test;

namespace {

class CliStop : public CliDirTest {
protected:
    // Renders kSkyScene with `options` (a sample count it cannot reach) to out.exr and
    // out.json, and sends `sig` once it has rendered for `cpu` seconds of CPU time; returns
    // the exit status.
    int renderAndSignal(int sig, const std::vector<std::string>& options, double cpu) {
        fs::remove(out());
        fs::remove(stats());
        std::vector<std::string> args{"render", "--quiet", "--spp", "100000000", "--stats", stats(), write("s.pbrt", kSkyScene),
                                      "-o", out()};
        args.insert(args.end(), options.begin(), options.end());
        RunningPathspace p(args);
        EXPECT_TRUE(p.waitUntilRendering(cpu)) << "pathspace exited or hung before rendering";
        EXPECT_TRUE(p.signalAndWaitTaken(sig));
        return p.wait();
    }
    // CPU seconds a Metropolis render of kSkyScene with `integrator` takes to load, bootstrap
    // and start its chains (measured by a render of one mutation per pixel), so that a signal
    // reaches chains that have run for a given time whatever this machine's speed: the
    // bootstrap is a fixed amount of work, seconds under the sanitizers on a slow machine.
    double metropolisStartCpu(const std::string& integrator) {
        auto childCpu = [] {
            rusage u{};
            getrusage(RUSAGE_CHILDREN, &u);
            return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
                   1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
        };
        const double before = childCpu();
        const Result r = runPathspace("render --quiet --spp 1 --integrator " + integrator +
                                      " --bootstrap 20000 --chains 64 " + write("s.pbrt", kSkyScene) + " -o " +
                                      (dir / "start.exr").string());
        EXPECT_EQ(r.status, 0) << r.out;
        return childCpu() - before;
    }
    std::string out() const { return (dir / "out.exr").string(); }
    std::string stats() const { return (dir / "out.json").string(); }
    nlohmann::json readStats() const { return nlohmann::json::parse(std::ifstream(stats())); }
};

}  // namespace

// SIGINT during any integrator's render: status 130 (README) and the image so far, exact
// within noise. (Light tracing is the noisiest here, the more so in spectral mode, the default,
// whose samples vary in colour: it renders longer.)
TEST_F(CliStop, InterruptWritesNormalisedImage) {
    for (const std::string integrator : {"path", "light", "bdpt"}) {
        SCOPED_TRACE(integrator);
        const bool light = integrator == "light";
        ASSERT_EQ(renderAndSignal(SIGINT, {"--integrator", integrator}, cpuSeconds(light ? 3.0 : 0.3)), 130);
        expectExactSkyImage(ps::readImage(out()), "SIGINT " + integrator, light ? 0.0 : 1.0);
        nlohmann::json j = readStats();
        EXPECT_TRUE(j["interrupted"].get<bool>());
        EXPECT_TRUE(j["stopped_early"].get<bool>());
    }
}

// SIGTERM (what a job scheduler sends) is handled as SIGINT is.
TEST_F(CliStop, TerminateWritesNormalisedImage) {
    for (const char* integrator : {"path", "bdpt"}) {
        SCOPED_TRACE(integrator);
        ASSERT_EQ(renderAndSignal(SIGTERM, {"--integrator", integrator}, cpuSeconds(0.3)), 130);
        expectExactSkyImage(ps::readImage(out()), std::string("SIGTERM ") + integrator);
        EXPECT_TRUE(readStats()["interrupted"].get<bool>());
    }
}

// A two-stage render stopped in its pilot (here certainly: the pilot is a quarter of 10^8
// samples per pixel) has no second-stage samples; the pilot's own mean per pixel is the image.
TEST_F(CliStop, InterruptDuringTwoStagePilotWritesNormalisedImage) {
    ASSERT_EQ(renderAndSignal(SIGINT, {"--adaptive", "twostage"}, cpuSeconds(0.3)), 130);
    expectExactSkyImage(ps::readImage(out()), "SIGINT in the two-stage pilot");
    EXPECT_LT(readStats()["spp_mean"].get<double>(), 1e8 / 4) << "the stop was not in the pilot";
}

// Two-stage MLT's pilot (on by default) stops at a Ctrl-C as the bootstrap does: a pilot of
// 2 x 10^8 samples, minutes of work, must end within seconds of the signal, with the black
// image of a stop before the chains (b unknown).
TEST_F(CliStop, InterruptDuringMetropolisPilotStopsIt) {
    for (const char* integrator : {"mmlt", "mlt"}) {
        SCOPED_TRACE(integrator);
        fs::remove(out());
        fs::remove(stats());
        RunningPathspace p({"render", "--quiet", "--spp", "1", "--stats", stats(), write("s.pbrt", kSkyScene), "-o", out(),
                            "--integrator", integrator, "--bootstrap", "20000", "--chains", "64", "--two-stage", "10000"});
        ASSERT_TRUE(p.waitUntilRendering(cpuSeconds(0.5))) << "pathspace exited or hung before rendering";
        const auto sent = std::chrono::steady_clock::now();
        ASSERT_TRUE(p.signalAndWaitTaken(SIGINT));
        EXPECT_EQ(p.wait(), 130);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
        EXPECT_LT(seconds, cpuSeconds(10.0)) << "the pilot did not stop at the signal";
        const nlohmann::json j = readStats();
        EXPECT_TRUE(j["interrupted"].get<bool>());
        EXPECT_EQ(j["metropolis"]["mutations"].get<long long>(), 0);
    }
}

// The time budget is not an interruption (status 0). A uniform render stops between passes;
// a two-stage render turns the budget into a sample budget for both stages (here it usually
// finishes within it; a cut second stage leaves the pilot's value in the pixels it missed).
TEST_F(CliStop, TimeBudgetWritesNormalisedImage) {
    for (const char* adaptive : {"none", "twostage"}) {
        SCOPED_TRACE(adaptive);
        fs::remove(out());
        ps::test::Result r = ps::test::runPathspace(std::string("render --quiet --spp 100000000 --time 0.5 --adaptive ") +
                                                    adaptive + " --stats " + stats() + " " + write("s.pbrt", kSkyScene) +
                                                    " -o " + out());
        ASSERT_EQ(r.status, 0) << r.out;
        nlohmann::json j = readStats();
        EXPECT_FALSE(j["interrupted"].get<bool>());
        EXPECT_LT(j["spp_mean"].get<double>(), 1e8);
        EXPECT_GT(j["spp_mean"].get<double>(), 1.0);
        expectExactSkyImage(ps::readImage(out()), std::string("--time, adaptive ") + adaptive);
    }
}

// A second Ctrl-C leaves at once with status 130, writing nothing. The render is one 16x16
// tile on one thread whose paths never end before depth 20000 (albedo 1 inside a closed
// sphere), so a first pass takes seconds and a process that honoured only the first signal
// would still be rendering when the second arrives, and would then write the image.
TEST_F(CliStop, SecondInterruptAbortsWithoutWriting) {
    const std::string scene = write("endless.pbrt", R"(LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" [ 60 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
Integrator "path" "integer maxdepth" [ 20000 ]
WorldBegin
AreaLightSource "diffuse" "rgb L" [ 0.1 0.1 0.1 ]
Material "diffuse" "rgb reflectance" [ 1 1 1 ]
ReverseOrientation
Shape "sphere" "float radius" [ 1 ]
)");
    RunningPathspace p({"render", "--quiet", "--threads", "1", "--stats", stats(), scene, "-o", out()});
    ASSERT_TRUE(p.waitUntilRendering(cpuSeconds(0.05)));
    ASSERT_TRUE(p.signalAndWaitTaken(SIGINT));
    ASSERT_TRUE(p.signalAndWaitTaken(SIGINT));
    EXPECT_EQ(p.wait(), 130);
    std::vector<std::string> left;
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
    EXPECT_EQ(left, std::vector<std::string>{"endless.pbrt"}) << "no image, temporary file or statistics";
}

namespace {

// The mean of kSkyScene's sphere and sky pixels (exact 0.5 and 1).
std::pair<double, double> skyClassMeans(const ps::Image& img) {
    double sum[2] = {0, 0};
    int n[2] = {0, 0};
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            double exact = exactSkyPixel(x, y);
            if (std::isnan(exact)) continue;
            ps::Spectrum v = img.get(x, y);
            sum[exact == 1.0] += (double(v.r) + v.g + v.b) / 3;
            ++n[exact == 1.0];
        }
    return {sum[0] / n[0], sum[1] / n[1]};
}

}  // namespace

// Metropolis renders stopped by SIGINT, SIGTERM or --time: the image is normalised by the
// mutations the chains made, not by those asked for (here 10^8 per pixel; a stop after a few
// million mutations normalised by the target would be 10^-3 of the exact image). A chain's
// pixels are correlated, so their spread is not the error: the class means are held to 3%
// of the exact values (the bootstrap's b is within 1%, the chains' noise under 1%).
TEST_F(CliStop, InterruptedMetropolisIsNormalisedByTheMutationsMade) {
    for (const char* integrator : {"pssmlt", "mmlt"})
        for (int how : {SIGINT, SIGTERM, 0}) {
            SCOPED_TRACE(std::string(integrator) + (how == SIGINT ? " SIGINT" : how == SIGTERM ? " SIGTERM" : " --time"));
            std::vector<std::string> options{"--integrator", integrator, "--bootstrap", "20000", "--chains", "64"};
            if (how) {
                ASSERT_EQ(renderAndSignal(how, options, metropolisStartCpu(integrator) + cpuSeconds(1.0)), 130);
            } else {
                fs::remove(out());
                ps::test::Result r = ps::test::runPathspace(
                    "render --quiet --spp 100000000 --time " + std::to_string(metropolisStartCpu(integrator) + cpuSeconds(1.0)) + " --integrator " +
                    integrator + " --bootstrap 20000 --chains 64 --stats " + stats() + " " + write("s.pbrt", kSkyScene) +
                    " -o " + out());
                ASSERT_EQ(r.status, 0) << r.out;
            }
            nlohmann::json j = readStats();
            EXPECT_EQ(j["interrupted"].get<bool>(), how != 0);
            EXPECT_TRUE(j["stopped_early"].get<bool>());
            const long long made = j["metropolis"]["mutations"].get<long long>();
            EXPECT_GT(made, 10000);
            EXPECT_LT(made, 100000000LL * 32 * 24 / 10);
            auto [sphere, sky] = skyClassMeans(ps::readImage(out()));
            std::printf("%s: %lld mutations; sphere %.4f (exact 0.5), sky %.4f (exact 1)\n", integrator, made, sphere, sky);
            EXPECT_NEAR(sphere, 0.5, 0.015);
            EXPECT_NEAR(sky, 1.0, 0.03);
        }
}
