// Checkpoints of Metropolis renders (pssmlt, mmlt, mlt): a checkpoint holds the bootstrap's
// results and every chain's whole state, so a render resumed from one, on any number of
// processes and threads, gives the uninterrupted render's image, variance and statistics
// bit for bit; a damaged checkpoint or one of other settings is refused.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "furnace_scene.h"
#include "run_mpi.h"

namespace fs = std::filesystem;
using namespace ps::test;

namespace {

class MetropolisCheckpoint : public SkyRenderTest {
protected:
    // A render of the furnace to NAME.pfm (with its variance) and NAME.json, by one plain
    // process (processes == 0) or under mpirun; its exit status and output (with its progress
    // bar's last line unless quiet).
    Result render(const std::string& name, const std::string& integrator, const std::string& options, int processes = 0,
                  bool quiet = true) {
        const std::string args = std::string("render ") + (quiet ? "--quiet " : "") + write("furnace.pbrt", kFurnace) +
                                 " --integrator " + integrator +
                                 " --bootstrap " + bootstrap + " --chains 13 " + options + " --aov variance -o " +
                                 path(name + ".pfm") +
                                 " --stats " + path(name + ".json");
        return processes == 0 ? runPathspace(args) : runMpi(processes, args);
    }
    std::string bootstrap = "3000";
    // NAME's image and variance have REF's bits, and its chains made the same mutations,
    // with the same acceptance, tracing the same rays.
    void expectSameRender(const std::string& name, const std::string& ref) {
        for (const char* suffix : {".pfm", ".variance.pfm"}) {
            const std::string a = bytes(path(ref + suffix));
            ASSERT_FALSE(a.empty());
            EXPECT_TRUE(a == bytes(path(name + suffix))) << name << suffix << " differs from " << ref << suffix;
        }
        const nlohmann::json a = stats(ref + ".json"), b = stats(name + ".json");
        EXPECT_EQ(b["metropolis"]["mutations"], a["metropolis"]["mutations"]);
        EXPECT_EQ(b["metropolis"]["acceptance_rate"], a["metropolis"]["acceptance_rate"]);
        EXPECT_EQ(b["metropolis"]["b"], a["metropolis"]["b"]);
        EXPECT_EQ(b["rays"], a["rays"]);
    }
};

const std::vector<std::string> kIntegrators{"pssmlt", "mmlt", "mlt"};

}  // namespace

// A checkpoint after every pass of 256 mutations per chain and one at the end: the render
// does not depend on the checkpoints it wrote. A render of fewer mutations per pixel (40, not
// 64: its last pass a short one), resumed with --spp raised to 64 and another thread count,
// equals the uninterrupted 64: a chain's course does not depend on how many mutations it is
// to make. mlt with direct lighting apart too: its path tracer's part is rendered again, from
// the same seed, on resuming.
TEST_F(MetropolisCheckpoint, ResumedEqualsUninterrupted) {
    std::vector<std::string> configurations = kIntegrators;
    configurations.push_back("mlt --mlt-direct 2");
    // Two-stage MLT: the pilot image is made again on resuming, the same bits.
    configurations.push_back("mmlt --two-stage 0.5");
    configurations.push_back("mlt --two-stage 0.5");
    for (const std::string& integrator : configurations) {
        SCOPED_TRACE(integrator);
        ASSERT_EQ(render("plain", integrator, "--spp 64 --threads 2").status, 0);
        const Result full = render("full", integrator, "--spp 64 --threads 2 --checkpoint " + path("ck") +
                                                           " --checkpoint-every 0");
        ASSERT_EQ(full.status, 0) << full.out;
        EXPECT_EQ(stats("full.json")["checkpoints"], 5);
        expectSameRender("full", "plain");
        const Result part = render("part", integrator, "--spp 40 --threads 2 --checkpoint " + path("ck40"), 0, false);
        ASSERT_EQ(part.status, 0) << part.out;
        EXPECT_NE(part.out.find("holds the bootstrap and 13 chains after"), std::string::npos) << part.out;
        const Result r = render("resumed", integrator, "--spp 64 --threads 1 --resume " + path("ck40"), 0, false);
        ASSERT_EQ(r.status, 0) << r.out;
        EXPECT_NE(r.out.find("--spp raised from its 40 to 64"), std::string::npos) << r.out;
        expectSameRender("resumed", "plain");
        // Its progress bar counts this run's mutations: it ends at 100%.
        const size_t bar = r.out.rfind("rendering [");
        ASSERT_NE(bar, std::string::npos) << r.out;
        EXPECT_NE(r.out.find("100.0%", bar), std::string::npos) << r.out.substr(bar, 80);
        // This run made the mutations the raise added, no more.
        const long long here = stats("resumed.json")["rank_samples"][0].get<long long>();
        EXPECT_EQ(here + stats("part.json")["metropolis"]["mutations"].get<long long>(),
                  stats("plain.json")["metropolis"]["mutations"].get<long long>());
    }
}

// Stopped by its time limit within a pass (each chain stands at its own pass boundary), a
// render writes a last checkpoint; resumed, it takes exactly the mutations left, to the
// uninterrupted image.
TEST_F(MetropolisCheckpoint, StoppedEarlyWritesALastCheckpoint) {
    for (const std::string integrator : {"pssmlt", "mlt"}) {
        SCOPED_TRACE(integrator);
        const std::string spp = integrator == "mlt" ? "2048" : "1024";
        ASSERT_EQ(render("full", integrator, "--threads 2 --spp " + spp).status, 0);
        fs::remove(path("ck"));
        ASSERT_EQ(render("part", integrator, "--threads 1 --spp " + spp + " --time " + std::to_string(cpuSeconds(0.3)) +
                                                 " --checkpoint " + path("ck") + " --checkpoint-every 1000")
                      .status,
                  0);
        const nlohmann::json part = stats("part.json");
        ASSERT_TRUE(part["stopped_early"].get<bool>()) << "the render ended before its time limit";
        // A loaded machine may have cut the bootstrap to fit the budget (startup_budget.h): the
        // start-up is then --bootstrap N's, N as the statistics say.
        if (const std::string n = std::to_string(part["metropolis"]["bootstrap_samples"].get<long long>()); n != bootstrap) {
            std::printf("%s: the bootstrap was cut to %s samples\n", integrator.c_str(), n.c_str());
            const std::string given = bootstrap;
            bootstrap = n;
            ASSERT_EQ(render("full", integrator, "--threads 2 --spp " + spp).status, 0);
            bootstrap = given;
        }
        EXPECT_EQ(part["checkpoints"], 1);
        ASSERT_TRUE(fs::exists(path("ck")));
        ASSERT_EQ(render("resumed", integrator, "--threads 2 --spp " + spp + " --resume " + path("ck")).status, 0);
        expectSameRender("resumed", "full");
        const long long before = part["metropolis"]["mutations"].get<long long>(),
                        after = stats("resumed.json")["rank_samples"][0].get<long long>(),
                        all = stats("full.json")["metropolis"]["mutations"].get<long long>();
        std::printf("%s: stopped after %lld of %lld mutations, resumed for %lld\n", integrator.c_str(), before, all, after);
        EXPECT_GT(before, 0);
        EXPECT_EQ(before + after, all) << "mutations lost or made twice";
    }
}

// A damaged checkpoint, or one of another render (each setting a chain's course depends on),
// is refused before anything is rendered: the output and the checkpoint stay as they were.
TEST_F(MetropolisCheckpoint, RefusesDamagedOrMismatchedCheckpoints) {
    ASSERT_EQ(render("make", "mlt", "--spp 16 --checkpoint " + path("ck") + " --checkpoint-every 0").status, 0);
    const std::string good = bytes(path("ck"));
    std::ofstream(path("truncated"), std::ios::binary) << good.substr(0, good.size() - 100);
    std::string corrupt = good;
    corrupt[good.size() - 10] ^= 0x10;  // a bit of the last chain's state
    std::ofstream(path("corrupt"), std::ios::binary) << corrupt;
    struct Case {
        std::string what, file, integrator, options, message;
    };
    const std::string kSame = "--bootstrap 3000 --chains 13";
    for (const Case& c : std::vector<Case>{
             {"truncated", "truncated", "mlt", kSame, "truncated or damaged"},
             {"corrupt chains", "corrupt", "mlt", kSame, "corrupt (its checksum does not match"},
             {"other chains", "ck", "mlt", "--bootstrap 3000 --chains 14", "chains 14 here, 13 in the checkpoint"},
             {"other bootstrap", "ck", "mlt", "--bootstrap 3001 --chains 13", "bootstrap 3001 here, 3000 in the checkpoint"},
             {"other mutations", "ck", "mlt", kSame + " --mlt-mutations lens=0", "mlt_mutations"},
             {"direct lighting apart", "ck", "mlt", kSame + " --mlt-direct 2", "mlt_mutations"},
             {"other integrator", "ck", "pssmlt", kSame, "integrator \"pssmlt\" here, \"mlt\" in the checkpoint"},
             {"other seed", "ck", "mlt", kSame + " --seed 5", "seed 5 here"}}) {
        SCOPED_TRACE(c.what);
        std::ofstream(path("out.pfm")) << "keep";
        const Result r = runPathspace("render --quiet " + write("furnace.pbrt", kFurnace) + " --integrator " + c.integrator +
                                      " --spp 16 " + c.options + " -o " + path("out.pfm") +
                                      " --resume " + path(c.file) + " --checkpoint " + path(c.file));
        EXPECT_EQ(r.status, 2) << r.out;
        EXPECT_NE(r.out.find("--resume \"" + path(c.file) + "\""), std::string::npos) << r.out;
        EXPECT_NE(r.out.find(c.message), std::string::npos) << r.out;
        EXPECT_TRUE(bytes(path("out.pfm")) == "keep") << "the output was overwritten";
    }
    EXPECT_TRUE(bytes(path("ck")) == good) << "the checkpoint was overwritten";
}

// Across processes (chain c runs on process c mod K, and rank 0 gathers every chain's state):
// a checkpoint written by 2 processes resumed by one, and one written by one process resumed
// by 2, give the uninterrupted image bit for bit.
TEST_F(MetropolisCheckpoint, ResumedOnAnotherNumberOfProcesses) {
    PS_SKIP_WITHOUT_MPI();
    for (const std::string& integrator : kIntegrators) {
        SCOPED_TRACE(integrator);
        const std::string every = " --checkpoint-every 0 --spp 64 --threads 1";
        ASSERT_EQ(render("one", integrator, "--checkpoint " + path("ck1") + every).status, 0);
        const Result two = render("two", integrator, "--checkpoint " + path("ck2") + every, 2);
        ASSERT_EQ(two.status, 0) << two.out;
        expectSameRender("two", "one");
        const Result from2 = render("from2", integrator, "--spp 64 --resume " + path("ck2"));
        ASSERT_EQ(from2.status, 0) << from2.out;
        expectSameRender("from2", "one");
        const Result from1 = render("from1", integrator, "--spp 64 --threads 1 --resume " + path("ck1"), 2);
        ASSERT_EQ(from1.status, 0) << from1.out;
        expectSameRender("from1", "one");
        EXPECT_EQ(stats("from1.json")["ranks"], 2);
    }
}
