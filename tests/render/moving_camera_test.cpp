// A moving camera with every integrator whose light paths connect to the lens: a path has
// one time, and light tracing's splats, BDPT's t = 1 strategies, and the Metropolis
// integrators' paths (the time a primary sample for pssmlt and mmlt, part of the path for
// Veach's mlt) must use the lens where it is at that time: its importance, densities and the
// film point a splat lands on. Each is compared with the path tracer, whose moving camera
// motion_blur_test.cpp checks against the exact time-averaged coverage; standard errors come
// from independent renders (agreement.h), as an MLT image's pixels are correlated.
#include <gtest/gtest.h>

#include <string>

#include "agreement.h"
#include "mlt_scenes.h"

using namespace ps;
using namespace ps::test;

namespace {

// The diffuse box of the Metropolis tests, its camera turning 6 degrees about the vertical
// axis and moving 0.15 sideways over the shutter (ActiveTransform around Camera: the end
// keyframe's camera-from-world), its sphere lifted and moving 0.2 sideways, so that lens
// connections and every other ray of a path must share the path's time.
std::string movingBox() {
    std::string scene = box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1");
    const std::string lookAt = "LookAt 0 0.5 2.2  0 0.5 0  0 1 0";
    scene.replace(scene.find(lookAt), lookAt.size(),
                  lookAt + "\n        ActiveTransform EndTime\n        Rotate 6 0 1 0\n        Translate 0.15 0 0\n"
                           "        ActiveTransform All");
    const std::string sphere = R"(Shape "sphere" "float radius" [ 0.2 ])";
    scene.replace(scene.find(sphere), sphere.size(),
                  "AttributeBegin\n        Translate -0.1 0.3 0\n        ActiveTransform EndTime\n        Translate 0.2 0 0\n"
                  "        ActiveTransform All\n        " + sphere + "\n        AttributeEnd");
    return scene;
}

}  // namespace

TEST(MovingCamera, SceneMovesCameraAndSphere) {
    setWarningsQuiet(true);
    auto s = buildScene(parseSceneString(movingBox(), ".", "<test>"));
    EXPECT_TRUE(s->camera().isMoving());
    EXPECT_TRUE(s->hasMotion());
}

TEST(MovingCamera, LightTracingAndBDPTAgreeWithPathTracing) {
    expectAgreement(AgreementCase{"moving camera", movingBox(), {"path", "light", "bdpt"}, 16, 16,
                                  {{"path", 32}, {"light", 16}, {"bdpt", 8}}, 0.02});
}

TEST(MovingCamera, PrimarySampleMetropolisAgreesWithPathTracing) {
    // Stratified bootstraps (pssmlt's and mmlt's per depth) smaller than the scene's 50000:
    // the path tracer's sigma is the larger (docs/testing.md).
    expectAgreement(AgreementCase{"moving camera", withBootstrap(movingBox(), 20000), {"path", "pssmlt", "mmlt"}, 64, 16,
                                  {{"path", 32}}, 0.02});
}

TEST(MovingCamera, VeachMLTAgreesWithPathTracing) {
    expectAgreement(AgreementCase{"moving camera", withBootstrap(movingBox(), 15000), {"path", "mlt"}, 64, 16,
                                  {{"path", 32}}, 0.02});
}
