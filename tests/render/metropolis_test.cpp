// Metropolis light transport over BDPT, both variants (transport/mlt/: primary-sample-space
// pssmlt and multiplexed mmlt), against answers they must reach: exact radiance in closed
// scenes, and BDPT's images (agreement.h: block and image means within 4 sigma), per path
// depth too. An MLT image's pixels are correlated through its chains, so every sigma here is
// measured across independent renders (seeds), never from one image.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "agreement.h"
#include "mlt_scenes.h"
#include "mc/estimator.h"
#include "render_helpers.h"
#include "transport/mlt/metropolis.h"

using namespace ps;
using namespace ps::test;

namespace {

// Every test runs for both variants: the parameter is the integrator's name. Both are held
// to the same detectable bias. A multiplexed sample evaluates one strategy of one depth:
// it costs a fraction of a BDPT sample and varies more, so mmlt runs two to four times the
// mutations.
class Metropolis : public ::testing::TestWithParam<std::string> {
protected:
    bool multiplexed() const { return GetParam() == "mmlt"; }
    int mutations(int n, int multiplexedFactor = 2) const { return multiplexed() ? multiplexedFactor * n : n; }
    // mmlt's bootstrap is per path depth (six of them here) and stratified: half the scenes'
    // still resolved its closed scenes to 0.5-0.6% (4 sigma; 0.41% and 0.38% with the scenes').
    std::string sized(const std::string& scene) const { return multiplexed() ? withBootstrap(scene, 25000) : scene; }
};

}  // namespace

INSTANTIATE_TEST_SUITE_P(Variants, Metropolis, ::testing::Values("pssmlt", "mmlt"),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

// The closed furnace (thesis ch. 11's chains must reach the same answer as independent
// samples): image mean within 4 sigma of the exact value, sigma across 16 renders.
TEST_P(Metropolis, ClosedFurnaceIsExact) {
    const std::string scene = sized(furnace());
    RunningStats means;
    for (int k = 0; k < 16; ++k) {
        RenderResult r = renderString(scene, mutations(64), 300 + uint64_t(k), 0, GetParam());
        RegionStats s = wholeImage(r.image);
        means.add((s.mean[0] + s.mean[1] + s.mean[2]) / 3);
        EXPECT_NEAR(r.metropolis.b, kFurnaceExact, 0.05 * kFurnaceExact);
    }
    double z = (means.mean() - kFurnaceExact) / means.standardError();
    std::printf("[ %-8s ] furnace: %.5f +- %.5f, exact %.5f (%.2f sigma; 4 sigma = %.2f%%)\n", GetParam().c_str(), means.mean(),
                means.standardError(), kFurnaceExact, z, 400 * means.standardError() / kFurnaceExact);
    EXPECT_LT(std::fabs(z), 4.0);
    EXPECT_LT(4 * means.standardError(), 0.01 * kFurnaceExact) << "too noisy";
}

// A point light of intensity I at the centre of a closed diffuse sphere of radius R and
// albedo rho: the direct irradiance I / R^2 is uniform, so is every bounce's radiance, and
// each bounce multiplies it by rho: L = I / (pi R^2) sum_{k=1..maxdepth} rho^k. Here I = pi,
// R = 1, rho = 0.5, maxdepth 5. Every path ends on a delta light, reachable only through
// connections (no camera subpath hits it): the chain's target is all connection strategies.
TEST_P(Metropolis, PointLightInADiffuseSphereIsExact) {
    const std::string scene = sized(pointLightInASphere());
    const double exact = 0.5 + 0.25 + 0.125 + 0.0625 + 0.03125;
    RunningStats means;
    for (int k = 0; k < 16; ++k) {
        RegionStats s = wholeImage(renderString(scene, mutations(64), 400 + uint64_t(k), 0, GetParam()).image);
        means.add((s.mean[0] + s.mean[1] + s.mean[2]) / 3);
    }
    double z = (means.mean() - exact) / means.standardError();
    std::printf("[ %-8s ] point light in a sphere: %.5f +- %.5f, exact %.5f (%.2f sigma; 4 sigma = %.2f%%)\n",
                GetParam().c_str(), means.mean(), means.standardError(), exact, z, 400 * means.standardError() / exact);
    EXPECT_LT(std::fabs(z), 4.0);
    EXPECT_LT(4 * means.standardError(), 0.01 * exact) << "too noisy";
}

// A diffuse box: block means and the image mean against BDPT's (the image mean to within a
// detectable 2%: each render's bootstrap costs as much as its chains).
TEST_P(Metropolis, AgreesWithBDPTOnADiffuseBox) {
    expectAgreement(AgreementCase{"diffuse box", box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), {"bdpt", GetParam()}, 16,
                                  16, {{GetParam(), mutations(64)}},
                                  0.02});
}

// Two-stage MLT (--two-stage, pilot_importance.h): the target is the luminance over a pilot
// image's brightness per tile, so each splat's luminance is B, not 1, and the image mean
// depends on where the chains are: four times the chains, each as long, and a 3% bias to
// detect (VeachMLT.TwoStageAgreesWithBDPT's); mmlt three times pssmlt's mutations.
TEST_P(Metropolis, TwoStageAgreesWithBDPT) {
    const int k = kMoreChains;
    const std::string twoStage = GetParam() + ":two-stage=0.5";
    expectAgreement(AgreementCase{"diffuse box, two-stage", withChainsTimes(box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), k),
                                  {"bdpt", twoStage}, 16, 16, {{twoStage, k * mutations(64, 6)}}, 0.03});
}

// Saturated colours: red and blue walls under a blue light. The target is luminance, the
// splats RGB: each channel's image mean against BDPT's (a chain that splatted the target's
// luminance as grey, or weighted the channels by it, keeps the luminance right and fails
// here), sigma across 28 renders of each (green, the dimmest channel, needs that many). In
// spectral mode green, a small difference of the wavelengths' large X, Y and Z, has 7-8x the
// relative sigma: BDPT 8x the samples, the chains 2048 mutations per pixel, pssmlt's in 16x
// the chains, mmlt's in 256x (pssmlt's green was noisier with more, mmlt's with fewer; 4 sigma
// 70-82% of the bound on three sets of seeds; 62 and 24 s).
TEST_P(Metropolis, AgreesWithBDPTOnASaturatedBoxPerChannel) {
    const bool spectral = defaultSpectral();
    std::string scene = box("1 1 12", "0.8 0.05 0.05", "0.05 0.05 0.8");
    if (spectral) scene = withChainsTimes(scene, multiplexed() ? 256 : 16);
    const int bdptSpp = spectral ? 128 : 16, mltSpp = spectral ? 2048 : mutations(48);
    RunningStats bdpt[3], mlt[3];
    for (int k = 0; k < 28; ++k) {
        RegionStats a = wholeImage(renderString(scene, bdptSpp, 100 + uint64_t(k), 0, "bdpt").image);
        RegionStats b = wholeImage(renderString(scene, mltSpp, 100 + uint64_t(k), 0, GetParam()).image);
        for (int c = 0; c < 3; ++c) {
            bdpt[c].add(a.mean[c]);
            mlt[c].add(b.mean[c]);
        }
    }
    for (int c = 0; c < 3; ++c) {
        double se = std::hypot(bdpt[c].standardError(), mlt[c].standardError());
        double z = (mlt[c].mean() - bdpt[c].mean()) / se;
        std::printf("[ %-8s ] saturated box, channel %d: bdpt %.5f, mlt %.5f +- %.5f (%.2f sigma; 4 sigma = %.2f%%)\n",
                    GetParam().c_str(), c, bdpt[c].mean(), mlt[c].mean(), se, z, 400 * se / bdpt[c].mean());
        EXPECT_LT(std::fabs(z), 4.0) << "channel " << c;
        EXPECT_LT(4 * se, 0.02 * bdpt[c].mean()) << "channel " << c << ": too noisy";
    }
}

// The chains, not the threads, own the random streams: the same bits at 1 and 4 threads.
TEST_P(Metropolis, SameBitsWhateverTheThreadCount) {
    const std::string scene = box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1");
    RenderResult a = renderString(scene, 4, 9, 1, GetParam()), b = renderString(scene, 4, 9, 4, GetParam());
    ASSERT_EQ(a.image.width, b.image.width);
    const PixelComparison d = comparePixels(a.image, b.image);
    EXPECT_EQ(d.differ, 0);
    EXPECT_EQ(d.nonFinite, 0);
    EXPECT_EQ(a.metropolis.mutations, 4LL * 24 * 24);
    EXPECT_GT(a.metropolis.acceptanceRate(), 0.05);
}

// No path carries light to the camera (the light faces away, into the floor of a closed
// room): a warning and a black image, not a crash (pbrt-v4's #77).
TEST_P(Metropolis, NoLightCarryingPathGivesABlackImage) {
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
    RenderResult r = renderString(scene, 4, 1, 0, GetParam());
    EXPECT_EQ(r.metropolis.b, 0.0);
    EXPECT_EQ(r.metropolis.mutations, 0);
    RegionStats s = wholeImage(r.image);
    EXPECT_EQ(s.mean[0] + s.mean[1] + s.mean[2], 0.0);
}

// pbrt-v4's Integrator "mlt" (multiplexed MLT) is our mmlt, with pbrt-v4's parameters and
// defaults: maxdepth 5, bootstrapsamples 100000, chains 1000, mutationsperpixel 100 (not the
// Sampler's pixelsamples), largestepprobability 0.3, sigma 0.01. "regularize" true (biased)
// warns and is ignored.
TEST(MetropolisOptions, PbrtMltIntegratorReadsPbrtParametersAndDefaults) {
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
    EXPECT_EQ(warningCount(), before);
    EXPECT_EQ(d.integrator, "mmlt");
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
    // regularize; no unused parameter.
    EXPECT_EQ(warningCount(), before + 1);
    EXPECT_EQ(p.integrator, "mmlt");
    EXPECT_EQ(p.maxDepth, 3);
    EXPECT_EQ(p.mltBootstrapSamples, 500);
    EXPECT_EQ(p.mltChains, 7);
    EXPECT_EQ(p.spp, 9);
    EXPECT_FLOAT_EQ(p.mltLargeStepProbability, 0.5f);
    EXPECT_FLOAT_EQ(p.mltSigma, 0.02f);
    EXPECT_FALSE(p.regularize);

    EXPECT_EQ(settings(R"(Integrator "pssmlt")").integrator, "pssmlt");
    EXPECT_EQ(settings(R"(Integrator "mmlt")").integrator, "mmlt");
    EXPECT_THROW(settings(R"(Integrator "mlt" "float sigma" [ 0 ])"), InputError);
    EXPECT_THROW(settings(R"(Integrator "mlt" "integer chains" [ 0 ])"), InputError);
}

// A caustic: a small area light above a glass sphere focuses on a diffuse floor. Its paths
// (L S S D E) reach the lens only through BDPT's light-subpath strategies, so the chain's
// target comes from the splats of t = 1 connections. Block and image means against BDPT.
// mmlt's image mean (b's error) and a dim block were too noisy for the 2% bound (4 sigma at
// 1.07 and 1.18 of agreement.h's bounds): it runs twice the bootstrap per depth and 4x the
// chains, each a quarter as long (4x the chains alone: 0.72-1.04 and 0.56-1.01). Measured over 4 sets of 16 seeds: 0.60-0.69 (image) and 0.55-0.68 (worst block) of
// the bounds in RGB mode, 0.65-0.70 and 0.45-0.59 over 3 sets in spectral mode.
TEST_P(Metropolis, AgreesWithBDPTOnAGlassCaustic) {
    std::string scene = glassCaustic();
    if (multiplexed()) scene = withChainsTimes(withBootstrap(scene, 300000), kMoreChains);
    expectAgreement(AgreementCase{"glass caustic", scene, {"bdpt", GetParam()}, 128, 16, {{GetParam(), mutations(80)}},
                                  0.02});
}

// An area light the camera sees only in a smooth mirror (behind the camera, facing the
// mirror), and a point light over the floor. The light's mirror image is reachable only by
// camera subpaths that hit it (s = 0), the point light only by connections: both kinds of
// strategy carry the chain. Block and image means against BDPT. pssmlt runs 4x the chains,
// each a quarter as long (the same cost): a block's sigma was at 0.83-1.03 of agreement.h's
// bound over 4 sets of 16 seeds, 0.60-0.78 with them (1.5x the mutations: 0.55-0.74).
TEST_P(Metropolis, AgreesWithBDPTOnALightSeenOnlyInAMirror) {
    std::string scene = lightSeenInAMirror();
    if (!multiplexed()) scene = withChainsTimes(scene, kMoreChains);
    expectAgreement(AgreementCase{"light seen in a mirror", scene, {"bdpt", GetParam()}, 32, 16,
                                  {{GetParam(), mutations(32, 4)}}, 0.02});
}

// Spectral mode: the wavelengths are a primary sample of the chain (moved by its mutations,
// restored by rejections), the target the luminance of the sensor's RGB. The glass caustic
// through a dispersive flint sphere on a coloured floor (under a larger light than the RGB
// case's, so that the caustic is less peaked), against spectral BDPT: block, image and
// per-channel means (agreement.h), sigma across renders. A strategy that misses the glass
// keeps all four wavelengths even where the sample's other subpath terminated them, as mmlt's
// single-strategy replay of a bootstrap sample needs.
TEST_P(Metropolis, AgreesWithBDPTSpectrallyOnADispersiveCaustic) {
    const std::string scene = dispersiveGlassCaustic();
    ASSERT_NE(scene.find("glass-F11"), std::string::npos);
    AgreementCase c{"spectral dispersive caustic", scene, {"bdpt", GetParam()}, 128, 16, {{GetParam(), mutations(80)}},
                    0.025};
    c.spectral = true;
    expectAgreement(c);
}

namespace {

// Per path depth, the mean luminance of BDPT's image of that depth (the MIS-weighted
// strategy images of the depth summed), over `renders` seeds.
std::vector<RunningStats> bdptDepthMeans(const std::string& text, int maxDepth, int spp, int renders) {
    std::vector<RunningStats> out(size_t(maxDepth + 1));
    for (int k = 0; k < renders; ++k) {
        auto scene = buildScene(parseSceneString(text, ".", "<test>"));
        BDPTIntegrator bdpt(*scene, maxDepth);
        bdpt.recordStrategies(maxDepth);
        RenderOptions o;
        o.spp = spp;
        o.seed = uint64_t(900 + k);
        o.progress = false;
        RenderResult r = render(*scene, bdpt, o);
        std::vector<double> depth(out.size(), 0.0);
        for (const auto& [name, img] : bdpt.strategyImages()->images(r.lightPaths)) {
            const int d = strategyDepth(name);
            if (name.find("_unweighted") != std::string::npos || d < 0) continue;
            depth[size_t(d)] += luminanceMean(img);
        }
        for (size_t d = 0; d < out.size(); ++d) out[d].add(depth[d]);
    }
    return out;
}

// One Metropolis render with each depth's image recorded.
RenderResult renderDepths(const std::string& text, const std::string& integrator, int mutations, uint64_t seed) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(text, ".", "<test>"));
    scene->settings().mltTwoStage = 0;  // the plain target's depth shares (render_helpers.h)
    auto integ = createIntegrator(integrator, *scene);
    auto* mlt = dynamic_cast<MetropolisIntegrator*>(integ.get());
    mlt->params().depthImages = true;
    RenderOptions o;
    o.spp = mutations;
    o.seed = seed;
    o.progress = false;
    return render(*scene, *integ, o);
}

}  // namespace

// Per-depth energy. Each depth's share of the image is what a chain must learn as it runs:
// chains whose depth is fixed at the start keep the bootstrap's estimate of it. So the
// bootstrap here is deliberately small (600 samples per depth): each depth's share, relative
// to the render's own total (the bootstrap's error in b, common to every depth, drops out),
// must still agree with BDPT's within 4 sigma (sigma across seeds), and its spread across
// seeds must shrink when the chains run 12x longer. Each depth's image itself is compared
// with BDPT's too (its sigma then includes the small bootstrap's error in b). A share is a
// ratio without b, so the bootstrap's start-up bias does not cancel in it as it does in
// b times the chains' average: a bias that fades as the chains run, here within about 1% of a
// share (measured with a bootstrap ten times larger), under the test's 4 sigma of 2-3%
// (pssmlt) and 7-9% (mmlt).
TEST_P(Metropolis, EachDepthsShareConvergesToBDPTs) {
    const int maxDepth = 3, renders = 24;
    std::string scene = box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1");
    scene.replace(scene.find("maxdepth\" [ 5 ]"), 15, "maxdepth\" [ 3 ]");
    scene.replace(scene.find("bootstrapsamples\" [ 50000 ]"), 27,
                  "bootstrapsamples\" [ " + std::to_string(multiplexed() ? 600 : 2400) + " ]");
    std::vector<RunningStats> bdpt = bdptDepthMeans(scene, maxDepth, 16, renders);
    std::vector<RunningStats> bdptShare(bdpt.size()), mlt(bdpt.size()), shareShort(bdpt.size()), shareLong(bdpt.size());
    double bdptTotal = 0;
    for (const RunningStats& d : bdpt) bdptTotal += d.mean();
    for (int k = 0; k < renders; ++k) {
        RenderResult shortRun = renderDepths(scene, GetParam(), mutations(16), 1500 + uint64_t(k));
        RenderResult longRun = renderDepths(scene, GetParam(), mutations(192), 1700 + uint64_t(k));
        ASSERT_EQ(longRun.depthImages.size(), mlt.size());
        double totalShort = luminanceMean(shortRun.image), totalLong = luminanceMean(longRun.image);
        for (size_t d = 0; d < mlt.size(); ++d) {
            double lum = luminanceMean(longRun.depthImages[d]);
            mlt[d].add(lum);
            shareLong[d].add(lum / totalLong);
            shareShort[d].add(luminanceMean(shortRun.depthImages[d]) / totalShort);
        }
    }
    for (size_t d = 0; d < mlt.size(); ++d) {
        // BDPT's share: its depth's mean over the sum of the depths' means (its relative
        // error is the depth's own, the total's being much smaller).
        double ref = bdpt[d].mean() / bdptTotal, refSe = bdpt[d].standardError() / bdptTotal;
        double se = std::hypot(refSe, shareLong[d].standardError());
        double z = (shareLong[d].mean() - ref) / se;
        double shrink = std::sqrt(shareLong[d].variance() / shareShort[d].variance());
        double seImage = std::hypot(bdpt[d].standardError(), mlt[d].standardError());
        double zImage = (mlt[d].mean() - bdpt[d].mean()) / seImage;
        std::printf("[ %-8s ] depth %zu: share bdpt %.4f, mlt %.4f +- %.4f (%.2f sigma; 4 sigma = %.2f%%), spread "
                    "x%.2f from 16 to 192 mutations per pixel; image %.2f sigma (4 sigma = %.1f%%)\n",
                    GetParam().c_str(), d, ref, shareLong[d].mean(), se, z, 400 * se / ref, shrink, zImage,
                    400 * seImage / bdpt[d].mean());
        EXPECT_LT(std::fabs(z), 4.0) << "depth " << d;
        EXPECT_LT(4 * se, 0.1 * ref) << "depth " << d << ": too noisy to detect a 10% error in a depth's share";
        // 1/sqrt(12) = 0.29 for independent batches; 0.7 leaves room for the spread's own
        // noise over 24 seeds and for the chains' correlation.
        EXPECT_LT(shrink, 0.7) << "depth " << d;
        EXPECT_LT(std::fabs(zImage), 4.0) << "depth " << d;
    }
}
