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

TEST(LightPathChoice, FloorIsZeroWithoutDeltaLights) {
    setWarningsQuiet(true);
    auto area = buildScene(parseSceneString(kCaustic, ".", "<test>"));
    EXPECT_EQ(lightOnlyFloor(*area), 0.0f);
    std::string withPoint = kCaustic;
    withPoint += R"(LightSource "point" "rgb I" [ 1 1 1 ] "point3 from" [ 0 2 1 ])";
    auto point = buildScene(parseSceneString(withPoint, ".", "<test>"));
    EXPECT_GT(lightOnlyFloor(*point), 0.0f);
    EXPECT_LT(lightOnlyFloor(*point), 1.0f);
}

// Path tracing finds the caustic only by hitting the small light through the sphere: its
// pilot's variance is hundreds of times BDPT's (measured 300x), far beyond the time's noise.
TEST(LightPathChoice, ACausticKeepsEveryLightSubpath) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(kCaustic, ".", "<test>"));
    BDPTIntegrator bdpt(*scene, 6);
    const LightPathChoice c = chooseLightPathShare(*scene, bdpt, 2, 1);
    std::printf("  variance x time: path %.3g, bdpt %.3g\n", c.pathVarianceTime, c.bdptVarianceTime);
    EXPECT_EQ(c.share, 1.0f);
    EXPECT_EQ(bdpt.lightPathShare(), 1.0f);
    EXPECT_GT(c.pathVarianceTime, 20 * c.bdptVarianceTime);
}
