// Every MIS heuristic (thesis ch. 9; --mis) is unbiased in the path tracer and in BDPT: the
// closed furnace (a diffuse sphere emitting Le, seen from inside: every pixel exactly
// Le (1 - 0.6^6) / 0.4 at maxdepth 5) within 4 sigma of its measured standard error, with
// sigma small enough that a 1.5% error fails. The heuristic must also reach the estimator:
// each gives an image of its own.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../app/furnace_scene.h"
#include "render_helpers.h"
#include "transport/integrator.h"

using namespace ps;
using namespace ps::test;

namespace {

RenderResult renderFurnace(const std::string& integrator, const std::string& mis, int spp) {
    setWarningsQuiet(true);
    const std::string text = std::string("Integrator \"path\" \"integer maxdepth\" [ 5 ]\n") + kFurnace;
    SceneDescription desc = parseSceneString(text, ".", "<test>");
    auto scene = buildScene(desc, false);
    scene->settings().spectral = false;
    auto integ = createIntegrator(integrator, *scene, mis);
    RenderOptions opts;
    opts.spp = spp;
    opts.seed = 5;
    opts.sampler = scene->settings().sampler;
    opts.progress = false;
    return render(*scene, *integ, opts);
}

class MisHeuristics : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

}  // namespace

TEST_P(MisHeuristics, UnbiasedOnTheClosedFurnace) {
    const auto [integrator, mis] = GetParam();
    // Uniform weights (none) keep every strategy's noise: BDPT needs 4x the samples with them.
    const bool uniformBdpt = std::string(integrator) == "bdpt" && std::string(mis) == "none";
    const RenderResult r = renderFurnace(integrator, mis, std::string(integrator) == "path" ? 64 : uniformBdpt ? 128 : 32);
    const RenderResult ref = renderFurnace(integrator, "", std::string(integrator) == "path" ? 64 : 32);
    const RegionStats st = wholeImage(r.image);
    std::printf("  %s --mis %s: %.5f +- %.5f, exact %.5f\n", integrator, mis, st.mean[1], st.stdErr[1], kFurnaceValue);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(st.mean[c], kFurnaceValue, 4 * st.stdErr[c] + 1e-5) << "channel " << c;
        EXPECT_LT(st.stdErr[c], 0.015 / 4 * kFurnaceValue) << "channel " << c;
    }
    if (std::string(mis) != "power") {
        EXPECT_NE(r.image.rgb, ref.image.rgb) << "--mis " << mis << " changed nothing";
    }
}

INSTANTIATE_TEST_SUITE_P(
    Furnace, MisHeuristics,
    ::testing::Combine(::testing::Values("path", "bdpt"),
                       ::testing::Values("balance", "power", "power:3", "power:0.5", "cutoff", "cutoff:0.5", "maximum",
                                         "none")),
    [](const ::testing::TestParamInfo<MisHeuristics::ParamType>& i) {
        std::string name = std::string(std::get<0>(i.param)) + "_" + std::get<1>(i.param);
        for (char& c : name)
            if (c == ':' || c == '.') c = '_';
        return name;
    });

// pssmlt and mmlt weigh BDPT's strategies too, and take --mis; light tracing and Veach's mlt
// have no strategies to weigh and refuse it, as path does in a scene with media for any
// heuristic but balance (its spectral MIS is the balance heuristic).
TEST(MisOption, WhereItAppliesAndWhereItIsRefused) {
    setWarningsQuiet(true);
    const std::string text = std::string("Integrator \"path\" \"integer maxdepth\" [ 5 ]\n") + kFurnace;
    auto scene = buildScene(parseSceneString(text, ".", "<test>"), false);
    for (const char* name : {"path", "bdpt", "pssmlt", "mmlt"})
        for (const char* mis : {"", "balance", "power:3", "cutoff:0.2", "maximum", "none"})
            EXPECT_NO_THROW(createIntegrator(name, *scene, mis)) << name << " " << mis;
    for (const char* name : {"light", "mlt"}) {
        EXPECT_NO_THROW(createIntegrator(name, *scene, ""));
        EXPECT_THROW(createIntegrator(name, *scene, "power"), InputError) << name;
    }
    EXPECT_THROW(createIntegrator("bdpt", *scene, "max"), InputError);
    auto fog = buildScene(parseSceneString(kFogFurnace, ".", "<test>"), false);
    EXPECT_NO_THROW(createIntegrator("path", *fog, ""));
    EXPECT_NO_THROW(createIntegrator("path", *fog, "balance"));
    EXPECT_THROW(createIntegrator("path", *fog, "power"), InputError);
    EXPECT_THROW(createIntegrator("path", *fog, "maximum"), InputError);
}
