// Rays through the edge two triangles share must hit one of them: a ray that slips between
// neighbours escapes a closed surface and darkens a lit plane (by 1.4e-4 of the image on the
// two-triangle ground plane of the exact-answer tests, before the scenes were built robust).
#include <gtest/gtest.h>

#include <random>

#include "geometry/ray.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "util/error.h"

using namespace ps;

namespace {

std::unique_ptr<Scene> quadScene(bool instanced) {
    setWarningsQuiet(true);
    const std::string quad = R"(Shape "trianglemesh" "point3 P" [ -50 0 -50  50 0 -50  50 0 50  -50 0 50 ]
                                  "integer indices" [ 0 1 2  0 2 3 ])";
    const std::string world = instanced ? "ObjectBegin \"q\"\n" + quad + "\nObjectEnd\nObjectInstance \"q\"\n" : quad;
    return buildScene(parseSceneString(R"(
        LookAt 0 1 0  0 0 0  0 0 1
        Camera "perspective"
        WorldBegin
    )" + world, ".", "<test>"));
}

// Rays at random points within 1e-6 of the shared diagonal (x = z), down and at an angle.
int missesAlongTheDiagonal(const Scene& scene, int n) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> along(-40, 40), across(-1e-6f, 1e-6f), tilt(-0.5f, 0.5f);
    int misses = 0;
    for (int i = 0; i < n; ++i) {
        const float t = along(rng), e = across(rng);
        const Vec3 target(t + e, 0, t - e);
        const Vec3 d = normalize(Vec3(tilt(rng), -1, tilt(rng)));
        Ray ray{target - d * 2.0f, d};
        SurfaceInteraction si;
        if (!scene.intersect(ray, si)) ++misses;
    }
    return misses;
}

}  // namespace

TEST(SharedEdge, RaysThroughTheDiagonalOfAQuadHitIt) {
    EXPECT_EQ(missesAlongTheDiagonal(*quadScene(false), 200000), 0);
}

TEST(SharedEdge, RaysThroughTheDiagonalOfAnInstancedQuadHitIt) {
    EXPECT_EQ(missesAlongTheDiagonal(*quadScene(true), 200000), 0);
}
