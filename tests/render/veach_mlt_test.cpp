// Veach's path-space Metropolis light transport (transport/mlt/veach/) against answers it
// must reach: exact radiance in closed scenes, and BDPT's images (agreement.h: block and
// image means within 4 sigma, sigma measured across independent renders: an MLT image's
// pixels are correlated through its chains). And the mutation's parts: its choice
// probabilities, and a chain whose proposals are whole new paths (the bookkeeping alone).
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "agreement.h"
#include "mc/estimator.h"
#include "mlt_scenes.h"
#include "mutation_cases.h"
#include "render_helpers.h"
#include "transport/mlt/veach/veach_mlt.h"

using namespace ps;
using namespace ps::test;

namespace {

// Bootstraps for mlt's stratified bootstrap (veach_mlt.cpp, stratifiedStart), below the
// scenes' 50000, which were sized for independent samples: on the diffuse box b's spread is
// about 0.55 of independent samples' (VeachMLTBootstrap), so 15000 resolve b about as well as
// 50000 did; the closed scenes keep half (their 4 sigma bound is 1%, not 2%).
constexpr int kSmallBootstrap = 15000, kStratifiedBootstrap = 25000;

// Mean over the image of (r + g + b) / 3 for `renders` seeds.
RunningStats greyMeans(const std::string& scene, int mutations, uint64_t seed0, int renders) {
    RunningStats means;
    for (int k = 0; k < renders; ++k) {
        RegionStats s = wholeImage(renderString(scene, mutations, seed0 + uint64_t(k), 0, "mlt").image);
        means.add((s.mean[0] + s.mean[1] + s.mean[2]) / 3);
    }
    return means;
}

void expectExact(const char* what, const RunningStats& means, double exact) {
    const double z = (means.mean() - exact) / means.standardError();
    std::printf("[ mlt ] %s: %.5f +- %.5f, exact %.5f (%.2f sigma; 4 sigma = %.2f%%)\n", what, means.mean(),
                means.standardError(), exact, z, 400 * means.standardError() / exact);
    EXPECT_LT(std::fabs(z), 4.0);
    EXPECT_LT(4 * means.standardError(), 0.01 * exact) << "too noisy";
}

}  // namespace

// The closed furnace: every path's vertices are all on one emitting diffuse sphere, so the
// mutations move through paths of every length; image mean within 4 sigma of exact.
TEST(VeachMLT, ClosedFurnaceIsExact) {
    expectExact("furnace", greyMeans(withBootstrap(furnace(), kStratifiedBootstrap), 64, 300, 16), kFurnaceExact);
}

// Every path ends on a point light (a delta position), reachable only by a light walk: the
// mutations must never try to reach it from the camera side.
TEST(VeachMLT, PointLightInADiffuseSphereIsExact) {
    expectExact("point light in a sphere", greyMeans(withBootstrap(pointLightInASphere(), kStratifiedBootstrap), 64, 400, 16),
                kPointLightInASphereExact);
}

TEST(VeachMLT, AgreesWithBDPTOnADiffuseBox) {
    expectAgreement(AgreementCase{"diffuse box", withBootstrap(box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), kSmallBootstrap),
                                  {"bdpt", "mlt"}, 16, 16, {{"mlt", 64}}, 0.02});
}

// Two-stage MLT (pilot_importance.h, `--two-stage F`): the target divided by a pilot image's
// brightness. Each splat's luminance is then B of its tile, not 1, so the image mean also
// depends on where the chains are: four times the chains, each as long (16 in spectral
// mode, whose wavelengths add to the spread of the splats' luminance), and a 3% bias to
// detect (the image mean's sigma was 0.40-0.64% over two builds). (On the glass caustic
// the image mean's sigma was 2.4% with the scene's chains and 1.4% with four times them,
// against BDPT's 0.24%: two-stage MLT spends on the dim floor what plain MLT spent on the
// bright caustic, which carries the image mean.)
TEST(VeachMLT, TwoStageAgreesWithBDPT) {
    const int k = defaultSpectral() ? 4 * kMoreChains : kMoreChains;
    expectAgreement(AgreementCase{"diffuse box, two-stage", withChainsTimes(box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), k),
                                  {"bdpt", "mlt:two-stage=0.5"}, 16, 16, {{"mlt:two-stage=0.5", k * 64}}, 0.03});
}

// Saturated colours: the target is luminance, the splats RGB; each channel against BDPT.
TEST(VeachMLT, AgreesWithBDPTOnASaturatedBoxPerChannel) {
    const std::string scene = box("1 1 12", "0.8 0.05 0.05", "0.05 0.05 0.8");
    RunningStats bdpt[3], mlt[3];
    for (int k = 0; k < 28; ++k) {
        RegionStats a = wholeImage(renderString(scene, 16, 100 + uint64_t(k), 0, "bdpt").image);
        RegionStats b = wholeImage(renderString(scene, 96, 100 + uint64_t(k), 0, "mlt").image);
        for (int c = 0; c < 3; ++c) {
            bdpt[c].add(a.mean[c]);
            mlt[c].add(b.mean[c]);
        }
    }
    for (int c = 0; c < 3; ++c) {
        const double se = std::hypot(bdpt[c].standardError(), mlt[c].standardError());
        const double z = (mlt[c].mean() - bdpt[c].mean()) / se;
        std::printf("[ mlt ] saturated box, channel %d: bdpt %.5f, mlt %.5f +- %.5f (%.2f sigma; 4 sigma = %.2f%%)\n", c,
                    bdpt[c].mean(), mlt[c].mean(), se, z, 400 * se / bdpt[c].mean());
        EXPECT_LT(std::fabs(z), 4.0) << "channel " << c;
        EXPECT_LT(4 * se, 0.02 * bdpt[c].mean()) << "channel " << c << ": too noisy";
    }
}

// Spectral mode: the wavelengths are part of the state (path_space.h MltVertex::lambda), kept
// by the mutations of vertices and moved by their own mutation; each channel against BDPT's.
// Saturated walls under a blackbody light, so that a wrong density of the wavelengths, or
// BxDFs left at the old ones, move the colour.
TEST(VeachMLT, AgreesWithBDPTSpectrallyOnASaturatedBox) {
    std::string scene = box("1 1 12", "0.8 0.05 0.05", "0.05 0.05 0.8");
    const std::string from = R"("rgb L" [ 1 1 12 ])";
    const size_t at = scene.find(from);
    ASSERT_NE(at, std::string::npos);
    scene.replace(at, from.size(), R"("blackbody L" [ 2700 ] "float scale" [ 6 ])");
    AgreementCase c{"spectral saturated box", withBootstrap(scene, kSmallBootstrap), {"bdpt", "mlt"}, 16, 16, {{"mlt", 96}}, 0.02};
    c.spectral = true;
    expectAgreement(c);
}

// Dispersion: every refraction in the flint glass keeps the first wavelength alone, which
// the path's contribution applies. The wavelength mutation leaves such paths to the others,
// and the perturbations move their wavelengths: without that, a chain's caustic kept its
// colour until the whole path was replaced, and blue's sigma across renders was 5x larger.
TEST(VeachMLT, AgreesWithBDPTSpectrallyOnADispersiveCaustic) {
    // Dispersion ten times flint glass' spreads the caustic's colours over the blocks.
    AgreementCase c{"spectral dispersive caustic", dispersiveGlassCaustic(R"("spectrum eta" [ 360 1.75  830 1.35 ])"),
                    {"bdpt", "mlt"}, 128, 16, {{"mlt", 256}}, 0.025};
    c.spectral = true;
    expectAgreement(c);
}

// Specular vertices: a caustic through a glass sphere (L S S D E), whose specular vertices
// only walks generate and no join may end at.
TEST(VeachMLT, AgreesWithBDPTOnAGlassCaustic) {
    expectAgreement(AgreementCase{"glass caustic", glassCaustic(), {"bdpt", "mlt"}, 128, 16,
                                  {{"mlt", 256}}, 0.02});
}

// A light seen only in a mirror (paths that end on an emitter hit by a camera walk) and a
// point light (paths that start on a delta position).
TEST(VeachMLT, AgreesWithBDPTOnALightSeenOnlyInAMirror) {
    const int k = defaultSpectral() ? kMoreChains : 1;  // mlt_scenes.h
    expectAgreement(AgreementCase{"light seen in a mirror", withChainsTimes(lightSeenInAMirror(), k), {"bdpt", "mlt"},
                                  32, 16, {{"mlt", k * 128}}, 0.02});
}

// A spot light seen in a mirror through a thin lens (mlt_scenes.h): the bokeh's L S E paths
// come only from light walks whose ray crosses the lens (t = 0, thesis §10.2), in the
// bootstrap and in the bidirectional mutation (PathSpace::reachLens); mlt rendered them
// black before. The bokeh fills one block and carries 97% of the image: the image mean is
// b's test (t = 0 densities 4% high: ratio 0.964, -9.6 sigma), the wall's blocks the
// chains' share between bokeh and wall. A chain leaves a bokeh path only by regenerating it
// whole (no perturbation moves L S E paths through a lens), so the chains must be long to
// show a wrong share: with 1024 mutations per pixel (4096 per chain) a mutation that never
// proposed t = 0 put 5 wall blocks beyond 4 sigma + 1%; at 256 (and 4x the chains) it passed.
TEST(VeachMLT, AgreesWithBDPTOnASpotSeenInAMirrorThroughALens) {
    expectAgreement(AgreementCase{"spot in a mirror through a lens", spotInAMirrorThroughALens(), {"bdpt", "mlt"}, 64, 16,
                                  {{"mlt", 1024}}, 0.02});
}

namespace {

// A sphere that emits and does not scatter (black: pbrt-v4's usual pure emitter), with the
// camera inside it: every pixel sees L = 1 (paths L E alone).
std::string insideABlackEmitter() {
    return std::string(R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 60 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        )") + mltIntegrator() + R"(
        WorldBegin
        Material "diffuse" "rgb reflectance" [ 0 0 0 ]
        AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
        ReverseOrientation
        Shape "sphere" "float radius" [ 1 ]
    )";
}

// The diffuse box with its sphere a black emitter, seen directly and lighting the walls.
std::string boxWithABlackEmitter() {
    std::string scene = box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1");
    const std::string from = R"(Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ])";
    scene.replace(scene.find(from), from.size(),
                  R"(Material "diffuse" "rgb reflectance" [ 0 0 0 ]
        AreaLightSource "diffuse" "rgb L" [ 2 2 2 ])");
    return scene;
}

}  // namespace

// An emitter whose BSDF has no diffuse or glossy lobe (black, or specular) is a surface of
// specular role where a camera walk hits it, yet as x0 it is a light like any other: a path
// that ends on it has the same f and densities whichever walk made it. (A camera walk's x0
// was taken for a point light: a black sphere seen directly lost its camera-side share of
// the balance heuristic: the image inside it was 0.084 of L, the box 7% dark.)
TEST(VeachMLT, EmittersThatDoNotScatterAreLightsFromEitherSide) {
    expectExact("inside a black emitter", greyMeans(insideABlackEmitter(), 64, 600, 16), 1.0);
    expectAgreement(AgreementCase{"box with a black emitter", boxWithABlackEmitter(), {"bdpt", "mlt"}, 16, 16,
                                  {{"mlt", 64}}, 0.02});
}

// Direct lighting apart (--mlt-direct): the path tracer's paths of at most one bounce plus the
// chains' longer ones make BDPT's image, on a diffuse box, on the mirror scene, where the
// light seen in the mirror (L S E, two edges) passes from the chains to the path tracer.
TEST(VeachMLT, DirectLightingApartAgreesWithBDPT) {
    expectAgreement(AgreementCase{"box, direct apart", box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), {"bdpt", "mlt:direct=4"},
                                  16, 16, {{"mlt:direct=4", 64}}, 0.02});
    expectAgreement(AgreementCase{"light seen in a mirror, direct apart", lightSeenInAMirror(), {"bdpt", "mlt:direct=4"},
                                  32, 16, {{"mlt:direct=4", 128}}, 0.02});
}

// The light seen through the glass sphere (L S S E, two bounces) stays with the chains.
TEST(VeachMLT, DirectLightingApartAgreesWithBDPTOnAGlassCaustic) {
    expectAgreement(AgreementCase{"glass caustic, direct apart", glassCaustic(), {"bdpt", "mlt:direct=4"}, 128, 16,
                                  {{"mlt:direct=4", 256}}, 0.02});
}

namespace {

// The box's film widened by the box filter's radius, half a pixel, on every side: a pixel
// more each way and the screen window grown to match. b integrates over that region (the
// chains' camera rays pass through the filter's margin, PathSpace::filmMargin, and the
// camera's importance is normalised over it), so it is the widened image's mean, not the
// film's (5% apart on the box: its margin sees the walls' dark front edges).
std::string onTheWidenedFilm(std::string scene) {
    auto replace = [&](const std::string& from, const std::string& to) {
        const size_t at = scene.find(from);
        if (at == std::string::npos) throw std::logic_error("onTheWidenedFilm: no \"" + from + "\"");
        scene.replace(at, from.size(), to);
    };
    replace(R"("integer xresolution" [ 24 ] "integer yresolution" [ 24 ])",
            R"("integer xresolution" [ 25 ] "integer yresolution" [ 25 ])");
    replace(R"(Camera "perspective" "float fov" [ 30 ])",
            R"(Camera "perspective" "float fov" [ 30 ] "float screenwindow" [ -1.0416667 1.0416667 -1.0416667 1.0416667 ])");
    return scene;
}

// Mean luminance of a scene's images over `seeds` seeds: their mean and its standard error.
double meanLuminance(const std::string& text, int spp, const char* integrator, int seeds, double* se) {
    RunningStats s;
    for (uint64_t seed = 1; seed <= uint64_t(seeds); ++seed) {
        const Image im = renderString(text, spp, seed, 0, integrator).image;
        double m = 0;
        for (size_t i = 0; i < im.rgb.size(); i += 3) m += Spectrum(im.rgb[i], im.rgb[i + 1], im.rgb[i + 2]).luminance();
        s.add(m / double(im.rgb.size() / 3));
    }
    *se = s.standardError();
    return s.mean();
}

}  // namespace

// What the chains leave out is exactly what the path tracer renders apart, and b is right
// without it: on the widened film, b equals BDPT's image mean, and b with direct lighting
// apart equals BDPT's mean less the path tracer's at maxdepth 1, within 4 sigma (b's from
// its bootstrap, whose spread across seeds bench/README.md measures; the images' across
// seeds). Each side of each comparison is an independent estimate.
TEST(VeachMLT, DirectLightingApartLeavesOnlyLongerPathsToTheChains) {
    const std::string scene = withBootstrap(box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), 400000);
    const std::string widened = onTheWidenedFilm(scene);
    std::string direct = widened;
    direct.replace(direct.find(R"("integer maxdepth" [ 5 ])"), 24, R"("integer maxdepth" [ 1 ])");
    double sb = 0, sp = 0;
    const double mb = meanLuminance(widened, 256, "bdpt", 8, &sb), mp = meanLuminance(direct, 256, "path", 8, &sp);
    const RenderResult all = renderString(scene, 1, 3, 0, "mlt"), apart = renderString(scene, 1, 4, 0, "mlt:direct=1");
    const double bAll = all.metropolis.b, bApart = apart.metropolis.b;
    const double sAll = std::hypot(sb, bAll * all.metropolis.bRelativeError);
    const double sApart = std::sqrt(sb * sb + sp * sp + std::pow(bApart * apart.metropolis.bRelativeError, 2));
    std::printf("  b %.5f, bdpt's mean %.5f (%.2f sigma); b without direct lighting %.5f, bdpt's less the path "
                "tracer's at maxdepth 1 %.5f (%.2f sigma)\n",
                bAll, mb, (bAll - mb) / sAll, bApart, mb - mp, (bApart - (mb - mp)) / sApart);
    EXPECT_GT(mp / mb, 0.1);
    EXPECT_LT(mp / mb, 0.9);
    EXPECT_LT(std::fabs(bAll - mb), 4 * sAll);
    EXPECT_LT(std::fabs(bApart - (mb - mp)), 4 * sApart);
    EXPECT_LT(4 * sApart, 0.02 * bApart) << "too noisy";
}

// The direct part is the path tracer's image of the same depths: where no path is longer
// (maxdepth 1, and 0: emission seen directly alone), the chains have nothing and the image
// is the path tracer's at that maxdepth, bit for bit.
TEST(VeachMLT, DirectPartIsThePathTracersImageOfTheSameDepths) {
    for (const char* depth : {"1", "0"}) {
        std::string scene = withBootstrap(box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), 2000);
        scene.replace(scene.find(R"("integer maxdepth" [ 5 ])"), 24,
                      std::string(R"("integer maxdepth" [ )") + depth + " ]");
        const RenderResult mlt = renderString(scene, 1, 5, 0, "mlt:direct=8");
        const RenderResult path = renderString(scene, 8, 5, 0, "path");
        EXPECT_EQ(mlt.metropolis.b, 0) << "maxdepth " << depth;
        const PixelComparison c = comparePixels(mlt.image, path.image);
        EXPECT_EQ(c.differ, 0) << "maxdepth " << depth;
        EXPECT_EQ(c.nonFinite, 0) << "maxdepth " << depth;
    }
}

// Layered surfaces, sampled by the path space's own mixture (MltVertex::mixed): a smooth-
// coated diffuse sphere (its coating's mirror and the rest) and a back wall of conductor
// under a rough coating, f being the layered BxDFs' deterministic estimates in both.
std::string coatedBox() {
    std::string scene = box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1");
    auto replace = [&](const std::string& from, const std::string& to) { scene.replace(scene.find(from), from.size(), to); };
    replace(R"(Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ])",
            R"(Material "coateddiffuse" "rgb reflectance" [ 0.5 0.5 0.8 ])");
    replace(R"(Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ])",
            R"(AttributeBegin
          Material "coatedconductor" "float interface.roughness" [ 0.2 ] "rgb reflectance" [ 0.9 0.6 0.3 ]
          Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ]
        AttributeEnd)");
    return scene;
}

TEST(VeachMLT, AgreesWithBDPTOnCoatedSurfaces) {
    expectAgreement(AgreementCase{"coated box", withBootstrap(coatedBox(), kSmallBootstrap), {"bdpt", "mlt"}, 16, 16,
                                  {{"mlt", 64}}, 0.02});
}

// An area light seen only in a smooth coating over a diffuse base: the mirror role of a
// mixed vertex (paths E S L), which the lens perturbation retraces.
std::string lightSeenInACoating() {
    std::string scene = lightSeenInAMirror();
    const std::string from = R"(Material "conductor" "rgb reflectance" [ 0.9 0.9 0.9 ] "float roughness" [ 0 ])";
    scene.replace(scene.find(from), from.size(), R"(Material "coateddiffuse" "rgb reflectance" [ 0.2 0.3 0.2 ])");
    return scene;
}

// An area light seen at grazing angles (about 80 degrees from the normal) in a smooth coating
// over a diffuse floor, where the coating's mirror weight R / cos differs most from R: paths
// E S L of the mixed vertex's mirror role, and the floor's diffuse light.
std::string lightSeenGrazingInACoating() {
    return std::string(R"(
        LookAt 0 0.4 3  0 0.2 0  0 1 0
        Camera "perspective" "float fov" [ 35 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        )") + mltIntegrator(100000) + R"(
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 4 4 4 ] "bool twosided" true
          Shape "bilinearmesh" "point3 P" [ -0.6 0.1 -2   0.6 0.1 -2   -0.6 0.9 -2   0.6 0.9 -2 ]
        AttributeEnd
        Material "coateddiffuse" "rgb reflectance" [ 0.2 0.3 0.2 ]
        Shape "bilinearmesh" "point3 P" [ -3 0 3   3 0 3   -3 0 -3   3 0 -3 ]
    )";
}

TEST(VeachMLT, AgreesWithBDPTOnALightSeenGrazingInACoating) {
    expectAgreement(AgreementCase{"light seen grazing in a coating", lightSeenGrazingInACoating(), {"bdpt", "mlt"}, 32, 16,
                                  {{"mlt", 512}}, 0.02});
}

// Each mutation makes a correct image: the bidirectional mutation (for ergodicity) with each
// other one alone, on the scene whose paths that mutation moves: block and image means
// against BDPT. The other tests run every mutation together.
class VeachMutation : public ::testing::TestWithParam<MutationCase> {};

TEST_P(VeachMutation, WithTheBidirectionalOneAgreesWithBDPT) { expectMutationAgreesAndApplies(GetParam()); }

std::string diffuseBox() { return box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"); }

INSTANTIATE_TEST_SUITE_P(
    Mutations, VeachMutation,
    ::testing::Values(
        MutationCase{"lens subpath, box", "lens-subpath=1,lens=0,multi-chain=0,caustic=0", diffuseBox, 16, 64, "lens subpath"},
        MutationCase{"lens subpath, mirror", "lens-subpath=1,lens=0,multi-chain=0,caustic=0", lightSeenInAMirror, 32, 128,
                     "lens subpath"},
        MutationCase{"lens perturbation, box", "lens-subpath=0,lens=1,multi-chain=0,caustic=0", diffuseBox, 16, 64,
                     "lens perturbation"},
        MutationCase{"lens perturbation, mirror", "lens-subpath=0,lens=1,multi-chain=0,caustic=0", lightSeenInAMirror, 32,
                     256, "lens perturbation"},
        MutationCase{"caustic perturbation, caustic", "lens-subpath=0,lens=0,multi-chain=0,caustic=1", glassCaustic, 128,
                     256, "caustic perturbation"},
        MutationCase{"multi-chain perturbation, caustic through glass", "lens-subpath=0,lens=0,multi-chain=1,caustic=0",
                     causticThroughGlass, 256, 256, "multi-chain perturbation", 0.03},
        MutationCase{"all, caustic through glass", "", causticThroughGlass, 256, 256, "multi-chain perturbation", 0.03},
        // Light through a slit: the paths the perturbations keep near the slit once found. A
        // quarter of the scene's bootstrap, a third of the time: b's error is a small part of
        // the image's sigma here (4 sigma 1.3% with 200000 samples, 1.4-1.8% with 50000).
        MutationCase{"lens subpath, door ajar", "lens-subpath=1,lens=0,multi-chain=0,caustic=0", doorAjar, 64, 128,
                     "lens subpath", 0.03, 50000},
        MutationCase{"lens perturbation, door ajar", "lens-subpath=0,lens=1,multi-chain=0,caustic=0", doorAjar, 64, 128,
                     "lens perturbation", 0.03, 50000},
        MutationCase{"all, door ajar", "", doorAjar, 64, 128, "lens perturbation", 0.03, 50000},
        MutationCase{"lens perturbation, light seen in a coating", "lens-subpath=0,lens=1,multi-chain=0,caustic=0",
                     lightSeenInACoating, 64, 1024, "lens perturbation"},
        // Uneven weights: the probability of choosing the bidirectional mutation then differs
        // by up to 16x between paths that admit the caustic perturbation and paths that do
        // not, so T(y -> x) must take it at y.
        MutationCase{"uneven weights, caustic", "lens-subpath=0.2,lens=0.2,multi-chain=0,caustic=15", glassCaustic, 128,
                     256, "caustic perturbation"}),
    [](const ::testing::TestParamInfo<MutationCase>& i) {
        std::string n;
        for (const char* p = i.param.name; *p; ++p) n += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
        return n;
    });

// The chain's bookkeeping alone (bootstrap, b, expected values, the acceptance ratio with
// T): with whole new paths as proposals, T(x -> y) is the density the bootstrap uses, and
// the image must be BDPT's whatever the bidirectional mutation's own densities are.
TEST(VeachMLT, RegeneratingWholePathsGivesBDPTsImage) {
    const std::string scene = box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1");
    RunningStats bdpt, mlt;
    for (int k = 0; k < 16; ++k) {
        bdpt.add(luminanceMean(renderString(scene, 16, 500 + uint64_t(k), 0, "bdpt").image));
        setWarningsQuiet(true);
        auto s = buildScene(parseSceneString(scene, ".", "<test>"));
        MetropolisParams mp;
        mp.bootstrapSamples = 50000;
        mp.chains = 64;
        VeachMutations regenerate;
        regenerate.regenerate = true;
        VeachMLTIntegrator integrator(*s, s->settings().maxDepth, mp, regenerate);
        RenderOptions o;
        o.spp = 64;
        o.seed = 500 + uint64_t(k);
        o.progress = false;
        RenderResult r = render(*s, integrator, o);
        ASSERT_EQ(r.metropolis.kinds.size(), 1u);
        EXPECT_EQ(r.metropolis.kinds[0].name, "regenerate");
        mlt.add(luminanceMean(r.image));
    }
    const double se = std::hypot(bdpt.standardError(), mlt.standardError());
    const double z = (mlt.mean() - bdpt.mean()) / se;
    std::printf("[ mlt ] regenerating whole paths: bdpt %.5f, mlt %.5f +- %.5f (%.2f sigma; 4 sigma = %.2f%%)\n",
                bdpt.mean(), mlt.mean(), se, z, 400 * se / bdpt.mean());
    EXPECT_LT(std::fabs(z), 4.0);
    EXPECT_LT(4 * se, 0.02 * bdpt.mean()) << "too noisy";
}

// The chains, not the threads, own the random streams: the same bits at 1 and 4 threads;
// no NaN; every mutation counted; acceptance strictly between 0 and 1.
TEST(VeachMLT, SameBitsWhateverTheThreadCount) {
    const std::string scene = box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1");
    RenderResult a = renderString(scene, 4, 9, 1, "mlt"), b = renderString(scene, 4, 9, 4, "mlt");
    ASSERT_EQ(a.image.width, b.image.width);
    const PixelComparison d = comparePixels(a.image, b.image);
    EXPECT_EQ(d.differ, 0);
    EXPECT_EQ(d.nonFinite, 0);
    EXPECT_EQ(a.metropolis.mutations, 4LL * 24 * 24);
    // Every mutation is counted once, and each one this scene's paths admit (the box has no
    // specular surface: no caustic or multi-chain perturbation) is sometimes accepted and
    // sometimes not.
    long long proposed = 0;
    for (const MetropolisStats::Kind& k : a.metropolis.kinds) {
        proposed += k.proposed;
        const double rate = MetropolisStats::rate(k.accepted, k.proposed);
        std::printf("[ mlt ] %s: %lld proposed, acceptance %.3f, %.3f failed\n", k.name.c_str(), k.proposed, rate,
                    k.proposed ? double(k.failed) / k.proposed : 0.0);
        if (k.name == "bidirectional" || k.name == "lens subpath" || k.name == "lens perturbation") {
            EXPECT_GT(rate, 0.05) << k.name;
            EXPECT_LT(rate, 0.95) << k.name;
        } else if (k.name == "wavelengths" && defaultSpectral()) {  // spectral mode only
            EXPECT_GT(rate, 0) << k.name;
            EXPECT_LT(rate, 1) << k.name;
        } else {
            EXPECT_EQ(k.proposed, 0) << k.name;
        }
    }
    EXPECT_EQ(proposed, a.metropolis.mutations);
}

// The mutation's choice probabilities: deleting d of n vertices sums to 1 over d, and the
// number inserted sums to 1 over its values wherever some value is possible; inserting
// nothing where nothing was deleted, or where an endpoint was, is impossible.
TEST(VeachMLT, MutationChoiceProbabilitiesAreDistributions) {
    setWarningsQuiet(true);
    auto s = buildScene(parseSceneString(box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), ".", "<test>"));
    VeachMLTIntegrator integrator(*s, 5, MetropolisParams{});
    const BidirectionalMutation& m = integrator.bidirectional();
    const int maxV = integrator.space().maxVertices();
    for (int n = 2; n <= maxV; ++n) {
        double sum = 0;
        for (int d = 0; d <= n; ++d) sum += BidirectionalMutation::deletionPmf(d, n);
        EXPECT_NEAR(sum, 1.0, 1e-12) << "n " << n;
        for (int d = 0; d <= n; ++d)
            for (int lo = d >= 1 ? 0 : 1; lo <= (d >= 1 ? n - d : n - 1); ++lo) {
                double insert = 0;
                for (int a = 0; a <= maxV; ++a) insert += m.insertionPmf(a, d, lo, n);
                EXPECT_TRUE(std::fabs(insert - 1) < 1e-12 || insert == 0) << n << " " << d << " " << lo;
                EXPECT_EQ(m.insertionPmf(0, 0, lo, n), 0.0);
                if (lo == 0 || lo + d == n) {
                    EXPECT_EQ(m.insertionPmf(0, d, lo, n), 0.0);
                }
            }
    }
}


// What mlt cannot do is refused with a clear error, never rendered wrongly: a smooth coating
// over a smooth conductor (a stochastic mirror weight). Lights at infinity render
// (veach_infinity_test.cpp checks their images).
TEST(VeachMLT, RefusesWhatItCannotRenderExactly) {
    const std::string base = R"(
        LookAt 0 0.5 2  0 0.5 0  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Shape "bilinearmesh" "point3 P" [ -0.2 1 -0.2   0.2 1 -0.2   -0.2 1 0.2   0.2 1 0.2 ]
        AttributeEnd
    )";
    auto refused = [](const std::string& scene, const std::string& why) {
        try {
            renderString(scene, 1, 1, 0, "mlt");
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
            return;
        }
        ADD_FAILURE() << "not refused: " << why;
    };
    // pbrt-v4's default coatedconductor: a smooth coating over a smooth conductor, also
    // inside a mix.
    const std::string smoothOverSmooth = "coatedconductor whose coating and conductor are both smooth";
    refused(base + "Material \"coatedconductor\"\nShape \"sphere\" \"float radius\" [ 0.2 ]\n", smoothOverSmooth);
    refused(base + "MakeNamedMaterial \"c\" \"string type\" \"coatedconductor\"\nMakeNamedMaterial \"d\" \"string type\" "
                   "\"diffuse\"\nMaterial \"mix\" \"string materials\" [ \"c\" \"d\" ]\nShape \"sphere\" \"float radius\" [ 0.2 ]\n",
            smoothOverSmooth);
    // The plain scene renders, and so do the other layered surfaces.
    EXPECT_NO_THROW(renderString(base + "Shape \"sphere\" \"float radius\" [ 0.2 ]\n", 1, 1, 0, "mlt"));
    EXPECT_NO_THROW(renderString(base + "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\nLightSource \"distant\"\n"
                                        "Shape \"sphere\" \"float radius\" [ 0.2 ]\n",
                                 1, 1, 0, "mlt"));
    EXPECT_NO_THROW(renderString(base + "Material \"coateddiffuse\"\nShape \"sphere\" \"float radius\" [ 0.2 ]\n", 1, 1, 0, "mlt"));
    // A black base has no lobe at all: nothing passes the smooth coating to be mirrored back.
    EXPECT_NO_THROW(renderString(base + "Material \"coateddiffuse\" \"rgb reflectance\" [ 0 0 0 ]\nShape \"sphere\" "
                                        "\"float radius\" [ 0.2 ]\n",
                                 1, 1, 0, "mlt"));
    EXPECT_NO_THROW(renderString(base + "Material \"coatedconductor\" \"float conductor.roughness\" [ 0.2 ]\nShape \"sphere\" "
                                        "\"float radius\" [ 0.2 ]\n",
                                 1, 1, 0, "mlt"));
}
