// Same scene, seed and thread count give bit-identical images; for the path tracer also
// across thread counts, because every pixel sample owns its random stream.
#include <gtest/gtest.h>

#include <filesystem>

#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

const char* kScene = R"(
    LookAt 0 1 3.9  0 1 0  0 1 0
    Camera "perspective" "float fov" [ 40 ]
    Film "rgb" "integer xresolution" [ 40 ] "integer yresolution" [ 30 ]
    Integrator "path" "integer maxdepth" [ 6 ]
    WorldBegin
    LightSource "infinite" "rgb L" [ 0.2 0.2 0.3 ]
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
      Shape "bilinearmesh" "point3 P" [ -0.3 1.9 -0.3  0.3 1.9 -0.3  -0.3 1.9 0.3  0.3 1.9 0.3 ]
    AttributeEnd
    Material "diffuse" "rgb reflectance" [ 0.7 0.6 0.5 ]
    Shape "bilinearmesh" "point3 P" [ -1 0 1  1 0 1  -1 0 -1  1 0 -1 ]
    Material "dielectric" "float eta" [ 1.5 ] "float roughness" [ 0.05 ]
    Translate 0 0.5 0
    Shape "sphere" "float radius" [ 0.5 ]
)";

}  // namespace

TEST(Determinism, SameSeedSameImageAcrossThreadCounts) {
    for (const std::string& sampler : samplerNames()) {
        SceneDescription desc = parseSceneString(kScene);
        auto scene = buildScene(desc);
        auto integrator = createIntegrator("path", *scene);
        auto run = [&](int threads, uint64_t seed) {
            RenderOptions o;
            o.spp = 8;
            o.seed = seed;
            o.threads = threads;
            o.sampler = sampler;
            o.progress = false;
            return render(*scene, *integrator, o).image.rgb;
        };
        auto a = run(1, 3), b = run(2, 3), c = run(2, 3), d = run(2, 4);
        EXPECT_EQ(a, b) << sampler;
        EXPECT_EQ(b, c) << sampler;
        EXPECT_NE(b, d) << sampler << ": the seed must change the image";
    }
}
