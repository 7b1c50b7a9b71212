// `--light-paths auto` (transport/light_path_choice.h): where path tracing wins, the share is 0
// unless delta lights make paths only light subpaths reach; a caustic that path tracing
// samples poorly keeps a light subpath for every sample.
#include <gtest/gtest.h>
#include "render_helpers.h"
#include "transport/bdpt.h"
#include "transport/light_path_choice.h"

using namespace ps;
using namespace ps::test;

namespace {

// A glass sphere under a small area light, out of view; its caustic on the floor is in it.
const char* kCaustic = R"(
    LookAt 0 0.25 2  0 0 0  0 1 0
    Camera "perspective" "float fov" [ 20 ]
    Film "rgb" "integer xresolution" [ 64 ] "integer yresolution" [ 64 ]
    WorldBegin
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
      Shape "bilinearmesh" "point3 P" [ -0.1 3 -0.1   0.1 3 -0.1   -0.1 3 0.1   0.1 3 0.1 ]
    AttributeEnd
    Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]
    Shape "bilinearmesh" "point3 P" [ -3 0 3   3 0 3   -3 0 -3   3 0 -3 ]
    AttributeBegin
      Material "dielectric" "float eta" [ 1.5 ]
      Translate 0 1.1 0
      Shape "sphere" "float radius" [ 0.5 ]
    AttributeEnd
)";

}  // namespace

TEST(LightPathChoice, FloorOnlyWherePathsNeedALightSubpath) {
    setWarningsQuiet(true);
    auto area = buildScene(parseSceneString(kCaustic, ".", "<test>"));
    EXPECT_EQ(lightOnlyFloor(*area), 0.0f);
    // A point light through the glass sphere: a caustic path tracing cannot sample.
    const std::string point = R"(LightSource "point" "rgb I" [ 1 1 1 ] "point3 from" [ 0 2 1 ])";
    auto caustic = buildScene(parseSceneString(kCaustic + point, ".", "<test>"));
    EXPECT_GT(lightOnlyFloor(*caustic), 0.0f);
    EXPECT_LT(lightOnlyFloor(*caustic), 1.0f);
    // The same light over diffuse surfaces alone: path tracing samples every path.
    std::string diffuse = kCaustic;
    diffuse.replace(diffuse.find("\"dielectric\" \"float eta\" [ 1.5 ]"), 33, "\"diffuse\"");
    EXPECT_EQ(lightOnlyFloor(*buildScene(parseSceneString(diffuse + point, ".", "<test>"))), 0.0f);
    // ... but seen through a lens it is a bokeh disk only light subpaths reach (t = 0).
    std::string lens = diffuse;
    lens.replace(lens.find("\"float fov\" [ 20 ]"), 18, "\"float fov\" [ 20 ] \"float lensradius\" 0.05 \"float focaldistance\" 2");
    EXPECT_GT(lightOnlyFloor(*buildScene(parseSceneString(lens + point, ".", "<test>"))), 0.0f);
}

namespace {

LightPathChoice choose(const Scene& scene, uint64_t seed) {
    BDPTIntegrator bdpt(scene, 6);
    RenderOptions o;
    o.threads = 2;
    o.seed = seed;
    LightPathChoice c = chooseLightPathShare(scene, bdpt, o);
    EXPECT_EQ(bdpt.lightPathShare(), c.share);
    std::printf("  seed %llu: variance x time: path %.3g, bdpt %.3g\n", (unsigned long long)seed, c.pathVarianceTime,
                c.bdptVarianceTime);
    return c;
}

}  // namespace

// Path tracing finds the caustic only by hitting the small light through the sphere. Its
// rare bright samples are few in a 2-spp pilot; measured against each pixel's own two
// samples' mean they would look tame (the relative variance of n samples is below n), so
// the pilot measures against a mean smoothed over both pilots and the neighbours, and
// chooses BDPT for every seed.
TEST(LightPathChoice, ACausticKeepsEveryLightSubpath) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(kCaustic, ".", "<test>"));
    for (uint64_t seed = 1; seed <= 3; ++seed) EXPECT_EQ(choose(*scene, seed).share, 1.0f) << seed;
}

// The bench's corridor lit by 200 ceiling panels (bench/scenes/many-lights): nearly all
// light is direct, which one light sample per vertex gets, so a BDPT sample's light subpath
// and its connections are cost without gain (bench/README.md: BDPT 2.3x path's relMSE at
// equal time; the pilot measures path 1.8x as efficient).
TEST(LightPathChoice, DirectLightGoesToThePathTracer) {
    setWarningsQuiet(true);
    const std::string file = std::string(PATHSPACE_SOURCE_DIR) + "/bench/scenes/many-lights/corridor.pbrt";
    auto scene = buildScene(parseSceneFile(file));
    for (uint64_t seed = 1; seed <= 2; ++seed) EXPECT_EQ(choose(*scene, seed).share, 0.0f) << seed;
}
