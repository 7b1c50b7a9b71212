// The agreement matrix: every variant of variants.cpp rendered by every integrator that can
// sample it, each compared (verify/block_statistics.h) with a reference that trusts no single
// integrator. A cell fails when its integrator differs from the reference by more than its
// measured spread allows, when the comparison could not catch a 2% bias, or when an integrator
// that should sample the variant is left out (or one that cannot is not).
//
// PATHSPACE_AGREEMENT_SCALE=K runs every cell with K times the samples (a longer tier, outside
// CI: docs/agreement-matrix.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/coverage.h"
#include "util/error.h"
#include "variants.h"
#include "verify/verify.h"

namespace ps::test {
namespace {

const std::string& dataDir() {
    static const std::string dir = (std::filesystem::temp_directory_path() / "pathspace-agreement-data").string();
    return dir;
}

const std::vector<Variant>& variants() {
    static const std::vector<Variant> v = agreementVariants(dataDir());
    return v;
}

// The smallest uniform relative bias each cell must be able to catch.
constexpr double kDetectable = 0.02;

int scale() {
    const char* s = std::getenv("PATHSPACE_AGREEMENT_SCALE");
    return s ? std::max(1, std::atoi(s)) : 1;
}

// Samples per pixel of one run (mutations per pixel for Metropolis), chosen so that 16 runs
// resolve a 2% bias on the base scene with room to spare. More runs of fewer samples cost
// the same and make the standard errors' own error smaller (Student's t with more degrees
// of freedom: a narrower bound for the same false-alarm rate).
verify::VerifyOptions options(const Variant& v, uint64_t seed) {
    verify::VerifyOptions o;
    o.runs = 16;
    o.seed = seed;
    const int k = v.sppScale * scale();
    o.spp = 32 * k;
    for (const auto& [name, scale] : v.integratorScale) o.sppOf[name] = o.spp * scale;
    // The bootstrap's estimate of b scales a Metropolis image: its error is the image mean's
    // (every Metropolis bootstrap is stratified: PrimarySampleSampler::stratifyFirstIteration,
    // and mlt's stratifiedStart). pssmlt's samples (whole BDPT samples) spread most; mmlt's
    // are per depth.
    o.configure = [k, &v](const std::string& name, RenderSettings& st) {
        const auto extra = v.bootstrapScale.find(name);
        st.mltBootstrapSamples = (name == "pssmlt" ? 20000 : name == "mmlt" ? 10000 : 5000) * k *
                                 (extra == v.bootstrapScale.end() ? 1 : extra->second);
    };
    return o;
}

// The Metropolis integrators run with 64 chains and the plain target: two-stage MLT's image
// mean moves far more between seeds (mmlt's by 10% per run at these sizes: resolving 2% would
// take hundreds of runs), so it keeps its own tests (TwoStageAgreesWithBDPT).
std::unique_ptr<Scene> load(const std::string& text, bool spectral) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(text, ".", "<variant>");
    auto scene = buildScene(desc, spectral);
    scene->settings().mltChains = 64;
    scene->settings().mltTwoStage = 0;
    return scene;
}

class AgreementMatrix : public ::testing::TestWithParam<size_t> {};

TEST_P(AgreementMatrix, EveryIntegratorAgrees) {
    const Variant& v = variants()[GetParam()];
    // PATHSPACE_AGREEMENT_DUMP=DIR writes the cell's scene to DIR/<test name>.pbrt, to render
    // it on its own (with `pathspace verify`, or by another renderer).
    if (const char* dir = std::getenv("PATHSPACE_AGREEMENT_DUMP"))
        std::ofstream(std::string(dir) + "/" + testName(v.name) + ".pbrt") << v.scene;
    auto scene = load(v.scene, v.spectral);

    // Coverage: exactly the integrators the variant names cannot sample it.
    std::set<std::string> cannot;
    for (const std::string& name : verify::allIntegrators())
        if (!missingPaths(*scene, name).empty()) cannot.insert(name);
    EXPECT_EQ(cannot, v.cannot) << v.name << ": the integrators that cannot sample it changed";

    std::unique_ptr<verify::Reference> reference;
    if (v.exact >= 0) {
        const verify::VerifyOptions o = options(v, 1);
        reference = std::make_unique<verify::Reference>(verify::exactReference(v.exact, o.blocksX * o.blocksY));
    } else if (!v.sameAs.empty()) {
        auto without = load(v.sameAs, v.spectral);
        verify::VerifyOptions o = options(v, 1000);
        o.integrators = {"path", "bdpt"};
        verify::VerifyReport r = verify::verifyScene(*without, o);
        reference = std::make_unique<verify::Reference>(
            verify::pooledOf({&r.results[0].runs, &r.results[1].runs}, "the scene without the feature"));
    }
    const verify::VerifyReport report = verify::verifyScene(*scene, options(v, 1), reference.get());

    std::string row = v.name + (v.spectral ? "" : " (rgb)") + ":";
    for (const verify::IntegratorResult& r : report.results) {
        char cell[96];
        if (!r.skipped.empty()) std::snprintf(cell, sizeof cell, " %s -", r.name.c_str());
        else std::snprintf(cell, sizeof cell, " | %s %.4f %+.1fs res %.1f%% chi2 %.0f/%.0f %.1fs", r.name.c_str(),
                           r.verdict.ratio, r.verdict.imageZ, 100 * r.verdict.resolution, r.verdict.chi2,
                           r.verdict.chi2Limit, r.seconds);
        row += cell;
    }
    std::printf("MATRIX %s\n", row.c_str());

    for (const verify::IntegratorResult& r : report.results) {
        if (!r.skipped.empty()) continue;
        ASSERT_TRUE(r.compared) << v.name << ": " << r.name << " has nothing to be compared with";
        if (auto known = v.knownBias.find(r.name); known != v.knownBias.end()) {
            std::printf("KNOWN %s: %s: %s\n", v.name.c_str(), r.name.c_str(), known->second.c_str());
            EXPECT_FALSE(r.verdict.agrees) << v.name << ": " << r.name << " agrees now: remove its knownBias marker";
            continue;
        }
        EXPECT_GT(r.runs.image().mean, 0.01) << v.name << ": " << r.name << ": the variant must be lit";
        EXPECT_TRUE(r.verdict.agrees) << v.name << ": " << r.name << " vs " << r.reference << ": " << r.verdict.why;
        EXPECT_LT(r.verdict.resolution, kDetectable)
            << v.name << ": " << r.name << " too noisy to catch a " << 100 * kDetectable << "% bias ("
            << 100 * r.verdict.resolution << "%)";
    }
}

std::string nameOf(const ::testing::TestParamInfo<size_t>& info) { return testName(variants()[info.param].name); }

INSTANTIATE_TEST_SUITE_P(Variants, AgreementMatrix, ::testing::Range<size_t>(0, variants().size()), nameOf);

}  // namespace
}  // namespace ps::test
