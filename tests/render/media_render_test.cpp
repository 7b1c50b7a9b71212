// Participating media (issue 36): transmittance by ratio tracking against exp(-sigma_t d),
// a light seen through an absorbing slab bounded by `interface` shapes, enclosed furnaces
// filled with scattering (and emitting) media, and the located errors of bad media.
#include <gtest/gtest.h>

#include <cmath>

#include "media_test_helpers.h"
#include "spectral_answer.h"
#include "transport/integrator.h"

using namespace ps;
using namespace ps::test;

// A homogeneous medium: exp(-sigma_t d) per channel, sigma_t chromatic (the hero's tracking
// weighs the other channels by their majorants' ratios).
TEST(MediaTransmittance, HomogeneousRatioTrackingIsExpMinusSigmaTD) {
    auto scene = sceneInMedium(R"("string type" "homogeneous" "rgb sigma_a" [ 0.1 0.3 0.6 ] "rgb sigma_s" [ 0.2 0.2 0.3 ]
                                  "float scale" [ 1.0 ])");
    const float d = 2;
    const auto got = ratioTracked(*scene, {0, 0, 0}, {0, 0, d}, 200000);
    expectTransmittance(got, {std::exp(-0.3 * d), std::exp(-0.5 * d), std::exp(-0.9 * d)}, "homogeneous");
}

// A uniform grid of one voxel (density 2) in the unit box: pbrt-v4 places the value at the
// cell's centre and interpolates towards zero beyond it, so along the box's axis through
// the centre the density is 2(1 - |2x - 1|/2) and the optical depth sigma_t * 2 * 0.75. The
// majorant (sigma_t * 2) exceeds sigma_t almost everywhere: real ratio tracking.
TEST(MediaTransmittance, UniformGridRatioTrackingIsExpMinusOpticalDepth) {
    auto scene = sceneInMedium(R"("string type" "uniformgrid" "float density" [ 2 ] "rgb sigma_a" [ 0.2 0.2 0.2 ]
                                  "rgb sigma_s" [ 0.3 0.5 0.8 ])");
    const auto got = ratioTracked(*scene, {-1, 0.5f, 0.5f}, {2, 0.5f, 0.5f}, 100000);
    expectTransmittance(got, {std::exp(-0.5 * 1.5), std::exp(-0.7 * 1.5), std::exp(-1.0 * 1.5)}, "uniformgrid");
}

// An rgbgrid of 2 x 1 x 1 voxels in a box scaled by the CTM (x from 0 to 4): the density
// rises linearly from voxel 0's centre (x = 1) to voxel 1's (x = 3); on [1, 3] the optical
// depth is the mean of the two values times 2.
TEST(MediaTransmittance, RgbGridIsPlacedByItsTransform) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(R"(
        Scale 4 1 1
        MakeNamedMedium "m" "string type" "rgbgrid" "integer nx" [ 2 ]
            "rgb sigma_a" [ 0.1 0.2 0.3  0.3 0.2 0.1 ] "rgb sigma_s" [ 0 0 0  0.2 0.2 0.2 ]
        Identity
        MediumInterface "" "m"
        Camera "perspective"
        WorldBegin
    )", ".", "<test>"), false);
    const auto got = ratioTracked(*scene, {1, 0.5f, 0.5f}, {3, 0.5f, 0.5f}, 100000);
    expectTransmittance(got, {std::exp(-0.3 * 2), std::exp(-0.3 * 2), std::exp(-0.3 * 2)}, "rgbgrid");
}

// A light of radiance 1 seen through a slab 1.5 thick of an absorbing, coloured medium between
// two `interface` quads (MediumInterface "slab" "" with N towards the vacuum): every
// orthographic ray crosses 1.5 of it, so each pixel is L exp(-sigma_a 1.5), per wavelength
// in spectral mode. The interfaces add no vertex and change no throughput.
TEST(MediaRender, LightSeenThroughAnAbsorbingSlab) {
    const std::string scene = slabScene(
        R"(MakeNamedMedium "slab" "string type" "homogeneous" "rgb sigma_a" [ 0.2 0.5 1.0 ] "rgb sigma_s" [ 0 0 0 ])",
        "Material \"interface\"\nMediumInterface \"slab\" \"\"");
    const bool spectral = defaultSpectral();
    RenderResult r = renderString(scene, spectral ? 512 : 256);
    const Lifted sigma{{0.2f, 0.5f, 1.0f}, SpectrumSource::rgbUnbounded(srgbColorSpace(), {0.2f, 0.5f, 1.0f}), 1};
    const auto exact = exactPixel(spectral, [](double L, double s) { return L * std::exp(-1.5 * s); }, emission({1, 1, 1}), sigma);
    expectImageMean(wholeImage(r.image), exact);
}

namespace {

void expectFurnace(const std::string& medium, int spp) {
    const bool spectral = defaultSpectral();
    RenderResult r = renderString(enclosedFurnace(medium), spp);
    const auto exact = exactPixel(spectral, itself, emission({1, 1, 1}));
    expectImageMean(wholeImage(r.image), exact);
}

}  // namespace

// Albedo 1, coloured sigma_s (each channel's own free flights, reached through the hero's),
// forward-scattering HG: next-event estimation from medium vertices and phase sampling,
// combined by spectral MIS, must add up to the wall's radiance.
TEST(MediaRender, ScatteringMediumFurnaceWithAlbedoOne) {
    expectFurnace(R"("string type" "homogeneous" "rgb sigma_a" [ 0 0 0 ] "rgb sigma_s" [ 0.5 1.5 3 ] "float g" [ 0.6 ])", 2048);
}

// The same with absorption balanced by emission Le = 1 (sigma_a Le along every flight).
TEST(MediaRender, EmittingMediumFurnace) {
    expectFurnace(R"("string type" "homogeneous" "rgb sigma_a" [ 1 0.5 0.2 ] "rgb sigma_s" [ 0.5 1 0.5 ] "float g" [ -0.3 ]
                     "rgb Le" [ 1 1 1 ])", 2048);
}

// ---- bad input ----

namespace {
}  // namespace

TEST(MediaErrors, UndefinedMediumIsALocatedError) {
    const std::string e = buildError("MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\nWorldBegin\n"
                                     "  MediumInterface \"smoke\" \"\"\n  Material \"interface\"\n  Shape \"sphere\"\n");
    EXPECT_NE(e.find("scene.pbrt:3:3"), std::string::npos) << e;
    EXPECT_NE(e.find("\"smoke\" is not defined"), std::string::npos) << e;
    // The camera's medium too.
    const std::string c = buildError("MediumInterface \"\" \"haze\"\nCamera \"perspective\"\nWorldBegin\n");
    EXPECT_NE(c.find("scene.pbrt:1:1"), std::string::npos) << c;
    EXPECT_NE(c.find("\"haze\" is not defined"), std::string::npos) << c;
}

TEST(MediaErrors, WrongSizedGridIsALocatedError) {
    const std::string e = buildError("WorldBegin\n  MakeNamedMedium \"g\" \"string type\" \"uniformgrid\" \"integer nx\" [ 2 ]\n"
                                     "    \"integer ny\" [ 2 ] \"float density\" [ 1 2 3 ]\n");
    EXPECT_NE(e.find("scene.pbrt:2:3"), std::string::npos) << e;
    EXPECT_NE(e.find("3 \"density\" values; expected nx*ny*nz = 2*2*1 = 4"), std::string::npos) << e;
    const std::string r = buildError("MakeNamedMedium \"g\" \"string type\" \"rgbgrid\" \"integer nz\" [ 2 ]\n"
                                     "  \"rgb sigma_s\" [ 1 1 1 ]\nWorldBegin\n");
    EXPECT_NE(r.find("scene.pbrt:1:1"), std::string::npos) << r;
    EXPECT_NE(r.find("\"sigma_s\" values"), std::string::npos) << r;
}

TEST(MediaErrors, UnsupportedMediaAreLocatedErrorsNotIgnored) {
    // (A homogeneous "preset" is supported since the subsurface material: subsurface_render_test.cpp.)
    const std::string v = buildError("WorldBegin\nMakeNamedMedium \"c\" \"string type\" \"nanovdb\"\n");
    EXPECT_NE(v.find("scene.pbrt:2:1"), std::string::npos) << v;
    EXPECT_NE(v.find("needs a \"filename\""), std::string::npos) << v;
}

// Every integrator has medium vertices; an emissive medium is refused by those without a
// strategy for its light (light tracing, Veach's mlt: medium_emission_test.cpp) rather than
// rendered wrong.
TEST(MediaErrors, IntegratorsWithoutMediaRefuse) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(enclosedFurnace(R"("string type" "homogeneous")"), ".", "<test>"), false);
    for (const char* name : {"path", "light", "bdpt", "pssmlt", "mmlt", "mlt"})
        EXPECT_NO_THROW(createIntegrator(name, *scene)) << name;
    auto emissive = buildScene(
        parseSceneString(enclosedFurnace(R"("string type" "homogeneous" "rgb Le" [ 1 1 1 ])"), ".", "<test>"), false);
    for (const char* name : {"path", "bdpt", "pssmlt", "mmlt"}) EXPECT_NO_THROW(createIntegrator(name, *emissive)) << name;
    for (const char* name : {"light", "mlt"}) {
        try {
            createIntegrator(name, *emissive);
            ADD_FAILURE() << name << " accepted an emissive medium";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("light emitted inside a medium"), std::string::npos) << e.what();
        }
    }
}

// Negative coefficients would run the majorant's flights backwards: errors, not renders.
TEST(MediaErrors, NegativeDensityOrScaleIsALocatedError) {
    const std::string d = buildError("WorldBegin\nMakeNamedMedium \"g\" \"string type\" \"uniformgrid\" \"float density\" [ -1 ]\n");
    EXPECT_NE(d.find("scene.pbrt:2:1"), std::string::npos) << d;
    EXPECT_NE(d.find("\"density\" values must be finite and at least 0"), std::string::npos) << d;
    const std::string s = buildError("WorldBegin\nMakeNamedMedium \"h\" \"string type\" \"homogeneous\" \"float scale\" [ -2 ]\n");
    EXPECT_NE(s.find("scene.pbrt:2:1"), std::string::npos) << s;
    EXPECT_NE(s.find("\"scale\" must be"), std::string::npos) << s;
}
