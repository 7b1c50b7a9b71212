// BDPT's strategies one by one (thesis §10.3, fig. 10.3): in a diffuse scene lit by an area
// light every strategy (s, t) can sample every path, so each one alone, unweighted, is an
// unbiased estimate of the image of paths of its depth: each must agree with
// the other strategies of that depth within 4 standard errors. And the MIS-weighted strategy
// images must sum to the BDPT image.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "mc/estimator.h"

#include "render_helpers.h"
#include "transport/bdpt.h"

using namespace ps;
using namespace ps::test;

namespace {

// Inside a diffuse sphere lit by a disk facing the camera, short of the wall. Any two points on a sphere's
// inside have the geometry term cos cos / d^2 = 1 / (4 R^2), and the disk keeps a gap to the
// wall, so no connection strategy meets the 1 / d^2 singularity of corners: every unweighted
// strategy has finite variance, and the spread of a few renders measures it.
const char* kScene = R"(
    LookAt 0 0 -0.9  0 0 1  0 1 0
    Camera "perspective" "float fov" [ 60 ]
    Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
    PixelFilter "box"
    Integrator "bdpt" "integer maxdepth" [ 3 ]
    WorldBegin
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 2 2 2 ]
      Translate 0 0 0.6
      Rotate 180 0 1 0
      Shape "disk" "float radius" [ 0.5 ]
    AttributeEnd
    Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
    Shape "sphere" "float radius" [ 1 ]
)";

}  // namespace

TEST(BdptStrategies, WeightedSumIsTheImageAndUnweightedAgree) {
    setWarningsQuiet(true);
    const int K = 16, maxDepth = 3;
    // Per strategy and render, the mean luminance of its unweighted image.
    std::map<std::string, std::vector<double>> unweighted;
    std::map<int, RunningStats> depthImage;  // the MIS-weighted image of each depth
    for (int k = 0; k < K; ++k) {
        SceneDescription desc = parseSceneString(kScene, ".", "<test>");
        auto scene = buildScene(desc);
        BDPTIntegrator bdpt(*scene, maxDepth);
        bdpt.recordStrategies(maxDepth);
        RenderOptions o;
        o.spp = 768;
        o.seed = uint64_t(50 + k);
        o.progress = false;
        RenderResult r = render(*scene, bdpt, o);
        Image sum(r.image.width, r.image.height);
        std::map<int, double> weightedOfDepth;
        for (const auto& [name, img] : bdpt.strategyImages()->images(r.lightPaths)) {
            if (name.find("_unweighted") != std::string::npos) {
                unweighted[name].push_back(luminanceMean(img));
                continue;
            }
            weightedOfDepth[strategyDepth(name)] += luminanceMean(img);
            for (size_t i = 0; i < sum.rgb.size(); ++i) sum.rgb[i] += img.rgb[i];
        }
        for (size_t i = 0; i < sum.rgb.size(); ++i)
            ASSERT_NEAR(sum.rgb[i], r.image.rgb[i], 1e-4 * (1 + std::fabs(r.image.rgb[i]))) << "pixel value " << i / 3;
        for (const auto& [depth, v] : weightedOfDepth) depthImage[depth].add(v);
    }
    std::map<std::string, double> variance;
    for (const auto& [name, xs] : unweighted) {
        RunningStats st;
        for (double x : xs) st.add(x);
        variance[name] = st.variance();
    }
    // Each strategy against the others of its depth, combined with inverse-variance weights:
    // an independent reference (a bias of the strategy under test does not move it, as it
    // would move the MIS-weighted image it dominates). The difference is taken per render, so
    // its spread across renders is its standard error, the correlation of strategies that
    // share a render's subpaths included.
    std::map<int, int> strategiesOfDepth;
    for (const auto& [name, xs] : unweighted) {
        int depth = strategyDepth(name);
        ++strategiesOfDepth[depth];
        if (depth == 0) continue;  // one strategy (the camera ray finds the light)
        double level = depthImage[depth].mean();
        ASSERT_GT(level, 0.001) << "depth " << depth;
        double wSum = 0;
        for (const auto& [other, v] : variance)
            if (other != name && strategyDepth(other) == depth) wSum += 1 / v;
        RunningStats d;
        for (int k = 0; k < K; ++k) {
            double ref = 0;
            for (const auto& [other, v] : variance)
                if (other != name && strategyDepth(other) == depth) ref += unweighted[other][size_t(k)] / (v * wSum);
            d.add(xs[size_t(k)] - ref);
        }
        std::printf("  depth %d: %s - others = %+.6f +- %.6f (%+.2f sigma; sigma %.3f%% of %.5f)\n", depth, name.c_str(),
                    d.mean(), d.standardError(), d.mean() / d.standardError(), 100 * d.standardError() / level, level);
        // The test must be able to detect a 2% bias of one strategy: 4 sigma under 2%.
        EXPECT_LT(d.standardError(), 0.005 * level) << name << ": too noisy to test";
        EXPECT_NEAR(d.mean(), 0.0, 4 * d.standardError()) << name << " disagrees with the other strategies";
    }
    for (int depth = 0; depth <= maxDepth; ++depth)
        EXPECT_EQ(strategiesOfDepth[depth], depth == 0 ? 1 : depth + 2) << "depth " << depth;
}

// Through a thin lens the t = 0 strategies (light subpaths that cross the lens, thesis §10.2)
// have images of their own, s<S>_t0 for S = 3 .. maxdepth + 2, and the weighted images,
// those included, sum to the render again. In this diffuse scene t = 0 carries little (its
// weight against the lens connection is about its density over 1 / lens area), but some.
TEST(BdptStrategies, ThinLensTZeroImagesCompleteTheSum) {
    setWarningsQuiet(true);
    const int maxDepth = 3;
    // The camera nearer the centre, so that a wide lens fits in the sphere: t = 0's weight
    // grows with the lens area (its density is 1 / area for the camera's strategies).
    std::string text = kScene;
    const std::string eye = "LookAt 0 0 -0.9", camera = "Camera \"perspective\" \"float fov\" [ 60 ]";
    text.replace(text.find(eye), eye.size(), "LookAt 0 0 -0.3");
    text.insert(text.find(camera) + camera.size(), " \"float lensradius\" [ 0.4 ] \"float focaldistance\" [ 1 ]");
    auto scene = buildScene(parseSceneString(text, ".", "<test>"));
    BDPTIntegrator bdpt(*scene, maxDepth);
    ASSERT_TRUE(bdpt.lensHits());
    bdpt.recordStrategies(maxDepth);
    RenderOptions o;
    o.spp = 64;
    o.seed = 3;
    o.progress = false;
    RenderResult r = render(*scene, bdpt, o);
    Image sum(r.image.width, r.image.height);
    double lensShare = 0;
    int lensImages = 0;
    for (const auto& [name, img] : bdpt.strategyImages()->images(r.lightPaths)) {
        const bool lens = name.find("_t0") != std::string::npos;
        if (lens) ++lensImages;
        if (name.find("_unweighted") != std::string::npos) continue;
        if (lens) lensShare += luminanceMean(img);
        for (size_t i = 0; i < sum.rgb.size(); ++i) sum.rgb[i] += img.rgb[i];
    }
    EXPECT_EQ(lensImages, 2 * maxDepth);
    for (size_t i = 0; i < sum.rgb.size(); ++i)
        ASSERT_NEAR(sum.rgb[i], r.image.rgb[i], 1e-4 * (1 + std::fabs(r.image.rgb[i]))) << "pixel value " << i / 3;
    const double share = lensShare / luminanceMean(r.image);
    std::printf("  t = 0's weighted images: %.2g of the image\n", share);
    EXPECT_GT(share, 0.0);
}
