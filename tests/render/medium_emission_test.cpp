// Emission inside participating media (issue 36) in every integrator that samples it: path,
// bdpt, pssmlt and mmlt, all through the camera walk's free flights (pbrt-v4's sigma_a Le at
// tentative collisions). Exact answers: a purely absorbing glowing medium around the camera
// gives Le (1 - exp(-sigma_a d)); a scattering one inside a black wall that emits the
// medium's own Le gives Le everywhere. BDPT files that light under its s = 0 strategies with
// weight 1, and nothing at maxdepth 0 (volpath's depth rule). Light tracing and Veach's mlt,
// which have no strategy for it, refuse such scenes with a message saying why.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "medium_emission_scenes.h"
#include "transport/bdpt.h"
#include "transport/coverage.h"

using namespace ps;
using namespace ps::test;

namespace {

struct Case {
    const char* integrator;
    int spp;
};
// Samples (mutations) per pixel for 16 renders of 8 x 8 pixels to resolve 2%.
constexpr Case kCases[] = {{"path", 64}, {"bdpt", 64}, {"pssmlt", 64}, {"mmlt", 64}};

}  // namespace

TEST(MediumEmission, AbsorbingGlowAroundTheCameraIsExact) {
    const bool spectral = defaultSpectral();
    const auto exact = glowingSphereExact(spectral);
    for (const Case& c : kCases) expectRendersMatch(glowingSphere(c.integrator, 5), c.integrator, c.spp, 16, exact);
}

// A scattering medium (albedo below 1, coloured, anisotropic) that emits Le = 1 where it
// absorbs, inside a black wall that emits 1: radiance 1 everywhere, so every pixel is the
// emission's colour (maxdepth 20: the paths beyond, each scattering keeping at most 2/3, are
// below 1e-3). BDPT weighs the wall's light over all its strategies and the medium's by
// s = 0 alone; the sum must still be exact. (path: MediaRender.EmittingMediumFurnace; pssmlt
// and mmlt, which mutate BDPT's samples: the agreement matrix's medium/emissive.)
TEST(MediumEmission, ScatteringGlowInsideAnEqualWallIsExact) {
    const bool spectral = defaultSpectral();
    // MediaRender.EmittingMediumFurnace's medium, in bdpt.
    const std::string scene = enclosedFurnace(R"("string type" "homogeneous" "rgb sigma_a" [ 1 0.5 0.2 ]
                                                 "rgb sigma_s" [ 0.5 1 0.5 ] "float g" [ -0.3 ] "rgb Le" [ 1 1 1 ])",
                                              "bdpt", 20);
    expectRendersMatch(scene, "bdpt", 64, 16, exactPixel(spectral, itself, emission({1, 1, 1})));
}

// pbrt-v4's volpath emits along a flight only after fewer than maxdepth scatterings: at
// maxdepth 0 the glowing sphere is black in every integrator, exactly.
TEST(MediumEmission, NothingAtMaxDepthZero) {
    for (const char* name : {"path", "bdpt"}) {
        const RenderResult r = renderString(glowingSphere(name, 0), 4, 3, 0, name);
        EXPECT_EQ(luminanceMean(r.image), 0.0) << name;
    }
}

// BDPT's figures: with sigma_s = 0 every path is the camera ray to an emitting point, the
// strategy (s = 0, t = 2), which holds the whole image, weighted and unweighted alike.
TEST(MediumEmission, BdptFilesItUnderS0) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(glowingSphere("bdpt", 5), ".", "<test>"), false);
    BDPTIntegrator bdpt(*scene, 5);
    bdpt.recordStrategies(5);
    RenderOptions o;
    o.spp = 16;
    o.seed = 5;
    o.progress = false;
    o.techniqueFigures = true;
    const RenderResult r = render(*scene, bdpt, o);
    const double image = luminanceMean(r.image);
    ASSERT_GT(image, 0);
    for (const auto& [name, img] : bdpt.strategyImages()->images(r.lightPaths)) {
        const double m = luminanceMean(img);
        if (name == "s0_t2" || name == "s0_t2_unweighted") EXPECT_NEAR(m, image, 1e-5 * image) << name;
        else EXPECT_EQ(m, 0.0) << name;
    }
    ASSERT_EQ(r.techniqueFigures.size(), r.techniques.size() + 1);
    for (size_t k = 0; k < r.techniques.size(); ++k)
        EXPECT_NEAR(r.techniqueFigures[k].share, r.techniques[k].name == "s0_t2" ? 1.0 : 0.0, 1e-9) << r.techniques[k].name;
}

// Light tracing and Veach's mlt have no strategy for light emitted inside a medium: they
// refuse, saying why and what to use; the others render it.
TEST(MediumEmission, LightAndMltRefuseWithTheReason) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(glowingSphere("path", 5), ".", "<test>"), false);
    for (const char* name : {"path", "bdpt", "pssmlt", "mmlt"}) {
        EXPECT_NO_THROW(createIntegrator(name, *scene)) << name;
        EXPECT_EQ(missingPaths(*scene, name), "") << name;
    }
    for (const char* name : {"light", "mlt"}) {
        EXPECT_NE(missingPaths(*scene, name), "") << name;  // light's first class here: the camera in a medium
        std::string missing;
        for (const UnsampledPaths& c : unsampledPaths(*scene, name))
            if (c.id == "medium-emission") missing = c.message;
        EXPECT_NE(missing.find("cannot render light emitted inside a medium"), std::string::npos) << missing;
        EXPECT_NE(missing.find("no light sampler chooses points in volumes"), std::string::npos) << missing;
        EXPECT_NE(missing.find("use path, bdpt, pssmlt or mmlt"), std::string::npos) << missing;
        try {
            createIntegrator(name, *scene);
            ADD_FAILURE() << name << " accepted an emissive medium";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()), missing) << name;
        }
    }
}
