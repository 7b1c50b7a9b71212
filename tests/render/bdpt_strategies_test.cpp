// BDPT's strategies one by one (thesis §10.3, fig. 10.3): in a diffuse box lit by an area
// light every strategy (s, t) can sample every path, so each one alone, unweighted, is an
// unbiased estimate of the image of paths of its depth: all must agree within 4 standard
// errors. And the MIS-weighted strategy images must sum to the BDPT image.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "mc/estimator.h"

#include "render_helpers.h"
#include "transport/bdpt.h"

using namespace ps;
using namespace ps::test;

namespace {

const char* kScene = R"(
    LookAt 0 0.5 2.2  0 0.5 0  0 1 0
    Camera "perspective" "float fov" [ 30 ]
    Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
    PixelFilter "box"
    Integrator "bdpt" "integer maxdepth" [ 3 ]
    WorldBegin
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]
      Shape "bilinearmesh" "point3 P" [ -0.3 0.99 -0.3   0.3 0.99 -0.3   -0.3 0.99 0.3   0.3 0.99 0.3 ]
    AttributeEnd
    Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 0 -0.5   0.5 0 -0.5 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 1 -0.5   0.5 1 -0.5   -0.5 1 0.5   0.5 1 0.5 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ]
    Material "diffuse" "rgb reflectance" [ 0.7 0.2 0.2 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   -0.5 0 -0.5   -0.5 1 0.5   -0.5 1 -0.5 ]
    Material "diffuse" "rgb reflectance" [ 0.2 0.7 0.2 ]
    Shape "bilinearmesh" "point3 P" [ 0.5 0 -0.5   0.5 0 0.5   0.5 1 -0.5   0.5 1 0.5 ]
)";

double luminanceMean(const Image& img) {
    RegionStats s = wholeImage(img);
    return 0.2126 * s.mean[0] + 0.7152 * s.mean[1] + 0.0722 * s.mean[2];
}

}  // namespace

TEST(BdptStrategies, WeightedSumIsTheImageAndUnweightedAgree) {
    setWarningsQuiet(true);
    const int K = 8, maxDepth = 3;
    // name -> per-render image means (unweighted), and the weighted-sum check per render.
    std::map<std::string, RunningStats> unweighted;
    for (int k = 0; k < K; ++k) {
        SceneDescription desc = parseSceneString(kScene, ".", "<test>");
        auto scene = buildScene(desc);
        BDPTIntegrator bdpt(*scene, maxDepth);
        bdpt.recordStrategies(maxDepth);
        RenderOptions o;
        o.spp = 64;
        o.seed = uint64_t(50 + k);
        o.progress = false;
        RenderResult r = render(*scene, bdpt, o);
        Image sum(r.image.width, r.image.height);
        for (const auto& [name, img] : bdpt.strategyImages()->images(r.lightPaths)) {
            bool isUnweighted = name.find("_unweighted") != std::string::npos;
            if (isUnweighted) unweighted[name].add(luminanceMean(img));
            else
                for (size_t i = 0; i < sum.rgb.size(); ++i) sum.rgb[i] += img.rgb[i];
        }
        for (size_t i = 0; i < sum.rgb.size(); ++i)
            ASSERT_NEAR(sum.rgb[i], r.image.rgb[i], 1e-4 * (1 + std::fabs(r.image.rgb[i]))) << "pixel value " << i / 3;
    }
    // Group by depth s + t - 2 and compare every strategy with the first of its depth.
    for (int depth = 0; depth <= maxDepth; ++depth) {
        std::vector<std::pair<std::string, const RunningStats*>> group;
        for (const auto& [name, st] : unweighted) {
            int s = 0, t = 0;
            std::sscanf(name.c_str(), "s%d_t%d", &s, &t);
            if (s + t - 2 == depth) group.push_back({name, &st});
        }
        ASSERT_EQ(group.size(), size_t(depth == 0 ? 1 : depth + 2)) << "depth " << depth;
        const RunningStats& a = *group[0].second;
        ASSERT_GT(a.mean(), 0.001);
        for (size_t i = 1; i < group.size(); ++i) {
            const RunningStats& b = *group[i].second;
            double se = std::sqrt(a.varianceOfMean() + b.varianceOfMean());
            std::printf("  depth %d: %s %.5f +- %.5f, %s %.5f +- %.5f\n", depth, group[0].first.c_str(), a.mean(),
                        a.standardError(), group[i].first.c_str(), b.mean(), b.standardError());
            EXPECT_LT(se, 0.1 * a.mean()) << group[i].first << ": too noisy to test";
            EXPECT_NEAR(a.mean(), b.mean(), 4 * se) << group[0].first << " vs " << group[i].first;
        }
    }
}
