// `--stats`' figures per technique and `--light-samples` through the real binary
// (docs/strategy-figures.md): the techniques listed, their shares summing to one, the
// estimator named; the option recorded, its refusals. Their statistics are checked in
// tests/render/technique_figures_test.cpp and light_samples_test.cpp.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "furnace_scene.h"
#include "run_binary.h"

namespace {

using ps::test::Result;
using ps::test::runPathspace;

class StrategyFigures : public ps::test::CliDirTest {
protected:
    nlohmann::json stats(const std::string& args) {
        const std::string scene = write("f.pbrt", ps::test::kFurnace);
        const std::string file = (dir / "s.json").string();
        const Result r = runPathspace("render --quiet " + scene + " -o " + (dir / "x.pfm").string() + " --stats " +
                                      file + " " + args);
        EXPECT_EQ(r.status, 0) << r.out;
        std::ifstream in(file);
        return nlohmann::json::parse(in);
    }
};

// Every technique's share, BDPT's (s, t) up to maxdepth and the path tracer's two, sums to one.
TEST_F(StrategyFigures, SharesSumToOne) {
    struct Case {
        std::string args, estimator;
        size_t techniques;
    };
    // bdpt at maxdepth 3: depths 0-3 have 2 + 3 + 4 + 5 strategies with t >= 1, less (1, 1).
    for (const Case& c : {Case{"--integrator path --spp 16", "scramblings", 2},
                          Case{"--integrator path --spp 16 --sampler independent", "sample variance", 2},
                          Case{"--integrator bdpt --maxdepth 3 --spp 16", "scramblings", 13}}) {
        SCOPED_TRACE(c.args);
        const nlohmann::json j = stats(c.args);
        EXPECT_EQ(j.at("variance_estimator"), c.estimator);
        const nlohmann::json& list = j.at("techniques").at("list");
        ASSERT_EQ(list.size(), c.techniques);
        double share = 0, mean = 0;
        for (const nlohmann::json& t : list) {
            share += t.at("share").get<double>();
            mean += t.at("mean").get<double>();
            EXPECT_GE(t.at("variance").get<double>(), 0);
        }
        EXPECT_NEAR(share, 1.0, 1e-6);
        EXPECT_NEAR(mean, j.at("techniques").at("image").at("mean").get<double>(), 1e-6 * mean);
        if (c.techniques == 2) {
            EXPECT_EQ(list[0].at("name"), "light");
            EXPECT_EQ(list[1].at("name"), "bsdf");
        } else {
            for (const nlohmann::json& t : list) {
                EXPECT_LE(t.at("depth").get<int>(), 3);
                EXPECT_FALSE(t.at("s") == 1 && t.at("t") == 1);
                EXPECT_EQ(t.at("splat"), t.at("t").get<int>() <= 1);
            }
            EXPECT_EQ(list[0].at("name"), "s0_t2");  // depth 0: the camera ray finds the light
        }
    }
}

// --light-samples: recorded in --stats; refused where no path vertex takes a light sample.
TEST_F(StrategyFigures, LightSamplesOption) {
    EXPECT_EQ(stats("--integrator path --spp 4 --light-samples 4").at("light_samples"), 4);
    EXPECT_EQ(stats("--integrator path --spp 4").at("light_samples"), 1);
    const std::string scene = write("f.pbrt", ps::test::kFurnace), fog = write("fog.pbrt", ps::test::kFogFurnace);
    const std::string out = " -o " + (dir / "x.pfm").string();
    for (const char* bad : {"0", "x", "2.5"}) {
        const Result r = runPathspace("render --quiet --spp 1 " + scene + out + " --light-samples " + std::string(bad));
        EXPECT_EQ(r.status, 2) << bad;
        EXPECT_NE(r.out.find("--light-samples"), std::string::npos) << r.out;
    }
    for (const char* refused : {"--integrator bdpt", "--integrator light", "--integrator pssmlt"}) {
        const Result r = runPathspace("render --quiet --spp 1 " + scene + out + " --light-samples 2 " + std::string(refused));
        EXPECT_EQ(r.status, 2) << refused;
        EXPECT_NE(r.out.find("--light-samples"), std::string::npos) << r.out;
    }
    const Result media = runPathspace("render --quiet --spp 1 " + fog + out + " --light-samples 2");
    EXPECT_EQ(media.status, 2);
    EXPECT_NE(media.out.find("participating media"), std::string::npos) << media.out;
}

}  // namespace
