// Primary-sample-space MLT over BDPT (transport/mlt/pssmlt.h) against answers it must reach:
// the closed furnace's exact radiance, and BDPT's images (agreement.h: block and image
// means within 4 sigma). An MLT image's pixels are correlated through its chains, so every
// sigma here is measured across independent renders (seeds), never from one image.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "agreement.h"
#include "mc/estimator.h"
#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

// The chain parameters of the tests: a bootstrap and chain count sized for small films. The
// image mean of an MLT render is b times a fixed total of splatted luminance, so its spread
// across seeds is mostly the bootstrap's estimate of b.
std::string mltIntegrator(int bootstrapSamples = 50000) {
    return R"(Integrator "pssmlt" "integer maxdepth" [ 5 ] "integer chains" [ 64 ] "integer bootstrapsamples" [ )" +
           std::to_string(bootstrapSamples) + " ]";
}

// A sphere lit from inside by its own emission, albedo 0.6: every pixel sees Le sum_k 0.6^k.
std::string furnace() {
    return std::string(R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 60 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        )") + mltIntegrator() + R"(
        WorldBegin
        AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
        Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
        ReverseOrientation
        Shape "sphere" "float radius" [ 1 ]
    )";
}
const double kFurnaceExact = (1 - std::pow(0.6, 6)) / 0.4;

// A 1 x 1 x 1 box open towards the camera with coloured walls; `light` and `walls` set the
// emission and the side walls' reflectances.
std::string box(const std::string& light, const std::string& left, const std::string& right) {
    return std::string(R"(
        LookAt 0 0.5 2.2  0 0.5 0  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        )") + mltIntegrator() + R"(
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ )" + light + R"( ]
          Shape "bilinearmesh" "point3 P" [ -0.2 0.99 -0.2   0.2 0.99 -0.2   -0.2 0.99 0.2   0.2 0.99 0.2 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 0 -0.5   0.5 0 -0.5 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 1 -0.5   0.5 1 -0.5   -0.5 1 0.5   0.5 1 0.5 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ]
        Material "diffuse" "rgb reflectance" [ )" + left + R"( ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   -0.5 0 -0.5   -0.5 1 0.5   -0.5 1 -0.5 ]
        Material "diffuse" "rgb reflectance" [ )" + right + R"( ]
        Shape "bilinearmesh" "point3 P" [ 0.5 0 -0.5   0.5 0 0.5   0.5 1 -0.5   0.5 1 0.5 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ]
        Shape "sphere" "float radius" [ 0.2 ]
    )";
}

}  // namespace

// The closed furnace (thesis ch. 11's chains must reach the same answer as independent
// samples): image mean within 4 sigma of the exact value, sigma across 16 renders.
TEST(PSSMLT, ClosedFurnaceIsExact) {
    const std::string scene = furnace();
    RunningStats means;
    for (int k = 0; k < 16; ++k) {
        RenderResult r = renderString(scene, 64, 300 + uint64_t(k), 0, "pssmlt");
        RegionStats s = wholeImage(r.image);
        means.add((s.mean[0] + s.mean[1] + s.mean[2]) / 3);
        EXPECT_NEAR(r.metropolis.b, kFurnaceExact, 0.05 * kFurnaceExact);
    }
    double z = (means.mean() - kFurnaceExact) / means.standardError();
    std::printf("[ pssmlt   ] furnace: %.5f +- %.5f, exact %.5f (%.2f sigma; 4 sigma = %.2f%%)\n", means.mean(),
                means.standardError(), kFurnaceExact, z, 400 * means.standardError() / kFurnaceExact);
    EXPECT_LT(std::fabs(z), 4.0);
    EXPECT_LT(4 * means.standardError(), 0.01 * kFurnaceExact) << "too noisy to detect a 1% bias";
}

// A point light of intensity I at the centre of a closed diffuse sphere of radius R and
// albedo rho: the direct irradiance I / R^2 is uniform, so is every bounce's radiance, and
// each bounce multiplies it by rho: L = I / (pi R^2) sum_{k=1..maxdepth} rho^k. Here I = pi,
// R = 1, rho = 0.5, maxdepth 5. Every path ends on a delta light, reachable only through
// connections (no camera subpath hits it): the chain's target is all connection strategies.
TEST(PSSMLT, PointLightInADiffuseSphereIsExact) {
    const std::string scene = std::string(R"(
        LookAt 0 0 -0.2  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 60 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        )") + mltIntegrator() + R"(
        WorldBegin
        LightSource "point" "rgb I" [ 3.14159265358979 3.14159265358979 3.14159265358979 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "sphere" "float radius" [ 1 ]
    )";
    const double exact = 0.5 + 0.25 + 0.125 + 0.0625 + 0.03125;
    RunningStats means;
    for (int k = 0; k < 16; ++k) {
        RegionStats s = wholeImage(renderString(scene, 64, 400 + uint64_t(k), 0, "pssmlt").image);
        means.add((s.mean[0] + s.mean[1] + s.mean[2]) / 3);
    }
    double z = (means.mean() - exact) / means.standardError();
    std::printf("[ pssmlt   ] point light in a sphere: %.5f +- %.5f, exact %.5f (%.2f sigma; 4 sigma = %.2f%%)\n",
                means.mean(), means.standardError(), exact, z, 400 * means.standardError() / exact);
    EXPECT_LT(std::fabs(z), 4.0);
    EXPECT_LT(4 * means.standardError(), 0.01 * exact) << "too noisy to detect a 1% bias";
}

// A diffuse box: block means and the image mean against BDPT's (the image mean to within a
// detectable 2%: each render's bootstrap costs as much as its chains).
TEST(PSSMLT, AgreesWithBDPTOnADiffuseBox) {
    expectAgreement(AgreementCase{"diffuse box", box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), {"bdpt", "pssmlt"}, 16,
                                  16, {{"pssmlt", 64}}, 0.02});
}

// Saturated colours: red and blue walls under a blue light. The target is luminance, the
// splats RGB: each channel's image mean against BDPT's (a chain that splatted the target's
// luminance as grey, or weighted the channels by it, keeps the luminance right and fails
// here), sigma across 20 renders of each.
TEST(PSSMLT, AgreesWithBDPTOnASaturatedBoxPerChannel) {
    const std::string scene = box("1 1 12", "0.8 0.05 0.05", "0.05 0.05 0.8");
    RunningStats bdpt[3], mlt[3];
    for (int k = 0; k < 20; ++k) {
        RegionStats a = wholeImage(renderString(scene, 16, 100 + uint64_t(k), 0, "bdpt").image);
        RegionStats b = wholeImage(renderString(scene, 48, 100 + uint64_t(k), 0, "pssmlt").image);
        for (int c = 0; c < 3; ++c) {
            bdpt[c].add(a.mean[c]);
            mlt[c].add(b.mean[c]);
        }
    }
    for (int c = 0; c < 3; ++c) {
        double se = std::hypot(bdpt[c].standardError(), mlt[c].standardError());
        double z = (mlt[c].mean() - bdpt[c].mean()) / se;
        std::printf("[ pssmlt   ] saturated box, channel %d: bdpt %.5f, pssmlt %.5f +- %.5f (%.2f sigma; 4 sigma = %.2f%%)\n",
                    c, bdpt[c].mean(), mlt[c].mean(), se, z, 400 * se / bdpt[c].mean());
        EXPECT_LT(std::fabs(z), 4.0) << "channel " << c;
        EXPECT_LT(4 * se, 0.02 * bdpt[c].mean()) << "channel " << c << ": too noisy to detect a 2% bias";
    }
}

// The chains, not the threads, own the random streams: the same bits at 1 and 4 threads.
TEST(PSSMLT, SameBitsWhateverTheThreadCount) {
    const std::string scene = box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1");
    RenderResult a = renderString(scene, 4, 9, 1, "pssmlt"), b = renderString(scene, 4, 9, 4, "pssmlt");
    ASSERT_EQ(a.image.width, b.image.width);
    int differ = 0, nonFinite = 0;
    for (int y = 0; y < a.image.height; ++y)
        for (int x = 0; x < a.image.width; ++x) {
            Spectrum p = a.image.get(x, y), q = b.image.get(x, y);
            differ += (p.r != q.r || p.g != q.g || p.b != q.b);
            nonFinite += !p.isFinite();
        }
    EXPECT_EQ(differ, 0);
    EXPECT_EQ(nonFinite, 0);
    EXPECT_EQ(a.metropolis.mutations, 4LL * 24 * 24);
    EXPECT_GT(a.metropolis.acceptanceRate(), 0.05);
}

// No path carries light to the camera (the light faces away, into the floor of a closed
// room): a warning and a black image, not a crash (pbrt-v4's #77).
TEST(PSSMLT, NoLightCarryingPathGivesABlackImage) {
    std::string scene = std::string(R"(
        LookAt 0 0.5 2  0 0.5 0  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
        )") + mltIntegrator() + R"(
        WorldBegin
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "bilinearmesh" "point3 P" [ -5 0 5   5 0 5   -5 0 -5   5 0 -5 ]
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Shape "bilinearmesh" "point3 P" [ -0.1 -1 -0.1   0.1 -1 -0.1   -0.1 -1 0.1   0.1 -1 0.1 ]
        AttributeEnd
    )";
    RenderResult r = renderString(scene, 4, 1, 0, "pssmlt");
    EXPECT_EQ(r.metropolis.b, 0.0);
    EXPECT_EQ(r.metropolis.mutations, 0);
    RegionStats s = wholeImage(r.image);
    EXPECT_EQ(s.mean[0] + s.mean[1] + s.mean[2], 0.0);
}

// pbrt-v4's Integrator "mlt" (multiplexed MLT) renders with pssmlt until mmlt exists, with
// pbrt-v4's parameters and defaults: maxdepth 5, bootstrapsamples 100000, chains 1000,
// mutationsperpixel 100 (not the Sampler's pixelsamples), largestepprobability 0.3, sigma
// 0.01. One warning says it is a stand-in; "regularize" true (biased) warns and is ignored.
TEST(PSSMLT, PbrtMltIntegratorReadsPbrtParametersAndDefaults) {
    setWarningsQuiet(true);
    auto settings = [](const std::string& integrator) {
        return buildScene(parseSceneString(R"(
            LookAt 0 0 5  0 0 0  0 1 0
            Camera "perspective"
            Sampler "independent" "integer pixelsamples" [ 4 ]
            )" + integrator + "\nWorldBegin\n",
                                           ".", "<test>"))
            ->settings();
    };
    int before = warningCount();
    RenderSettings d = settings(R"(Integrator "mlt")");
    EXPECT_EQ(warningCount(), before + 1);  // the stand-in
    EXPECT_EQ(d.integrator, "pssmlt");
    EXPECT_EQ(d.maxDepth, 5);
    EXPECT_EQ(d.mltBootstrapSamples, 100000);
    EXPECT_EQ(d.mltChains, 1000);
    EXPECT_EQ(d.spp, 100);
    EXPECT_FLOAT_EQ(d.mltLargeStepProbability, 0.3f);
    EXPECT_FLOAT_EQ(d.mltSigma, 0.01f);

    before = warningCount();
    RenderSettings p = settings(R"(Integrator "mlt" "integer maxdepth" [ 3 ] "integer bootstrapsamples" [ 500 ]
        "integer chains" [ 7 ] "integer mutationsperpixel" [ 9 ] "float largestepprobability" [ 0.5 ]
        "float sigma" [ 0.02 ] "bool regularize" true)");
    // regularize (the stand-in's warning, at the same place, is printed once); no unused parameter.
    EXPECT_EQ(warningCount(), before + 1);
    EXPECT_EQ(p.integrator, "pssmlt");
    EXPECT_EQ(p.maxDepth, 3);
    EXPECT_EQ(p.mltBootstrapSamples, 500);
    EXPECT_EQ(p.mltChains, 7);
    EXPECT_EQ(p.spp, 9);
    EXPECT_FLOAT_EQ(p.mltLargeStepProbability, 0.5f);
    EXPECT_FLOAT_EQ(p.mltSigma, 0.02f);
    EXPECT_FALSE(p.regularize);

    EXPECT_THROW(settings(R"(Integrator "mlt" "float sigma" [ 0 ])"), InputError);
    EXPECT_THROW(settings(R"(Integrator "mlt" "integer chains" [ 0 ])"), InputError);
}

// A caustic: a small area light above a glass sphere focuses on a diffuse floor. Its paths
// (L S S D E) reach the lens only through BDPT's light-subpath strategies, so the chain's
// target comes from the splats of t = 1 connections. Block and image means against BDPT.
TEST(PSSMLT, AgreesWithBDPTOnAGlassCaustic) {
    const std::string scene = std::string(R"(
        LookAt 0 2.2 2.6  0 0.3 0  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        )") + mltIntegrator(150000) + R"(
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 27 27 27 ]
          Shape "bilinearmesh" "point3 P" [ -0.15 2.5 -0.15   0.15 2.5 -0.15   -0.15 2.5 0.15   0.15 2.5 0.15 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]
        Shape "bilinearmesh" "point3 P" [ -3 0 3   3 0 3   -3 0 -3   3 0 -3 ]
        AttributeBegin
          Material "dielectric" "float eta" [ 1.5 ]
          Translate 0 0.9 0
          Shape "sphere" "float radius" [ 0.5 ]
        AttributeEnd
    )";
    expectAgreement(AgreementCase{"glass caustic", scene, {"bdpt", "pssmlt"}, 128, 16, {{"pssmlt", 64}}, 0.02});
}

// An area light the camera sees only in a smooth mirror (behind the camera, facing the
// mirror), and a point light over the floor. The light's mirror image is reachable only by
// camera subpaths that hit it (s = 0), the point light only by connections: both kinds of
// strategy carry the chain. Block and image means against BDPT.
TEST(PSSMLT, AgreesWithBDPTOnALightSeenOnlyInAMirror) {
    const std::string scene = std::string(R"(
        LookAt 0 1 3  0 0.7 0  0 1 0
        Camera "perspective" "float fov" [ 35 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        )") + mltIntegrator(200000) + R"(
        WorldBegin
        LightSource "point" "rgb I" [ 2 2 2 ] "point3 from" [ 0.6 1.5 1 ]
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 6 6 6 ] "bool twosided" true
          Shape "bilinearmesh" "point3 P" [ -0.4 0.6 3.5   0.4 0.6 3.5   -0.4 1.4 3.5   0.4 1.4 3.5 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -2 0 4   2 0 4   -2 0 -1   2 0 -1 ]
        Material "conductor" "rgb reflectance" [ 0.9 0.9 0.9 ] "float roughness" [ 0 ]
        Shape "bilinearmesh" "point3 P" [ -1 0 -1   1 0 -1   -1 2 -1   1 2 -1 ]
    )";
    expectAgreement(AgreementCase{"light seen in a mirror", scene, {"bdpt", "pssmlt"}, 32, 16, {{"pssmlt", 32}}, 0.02});
}
