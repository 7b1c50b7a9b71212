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

// One image of kScene; the same (integrator, sampler, threads, seed) must reproduce it.
std::vector<float> renderImage(const char* integrator, const char* sampler, int threads, uint64_t seed) {
    SceneDescription desc = parseSceneString(kScene);
    auto scene = buildScene(desc);
    auto integ = createIntegrator(integrator, *scene);
    RenderOptions o;
    o.spp = 8;
    o.seed = seed;
    o.threads = threads;
    o.sampler = sampler;
    o.progress = false;
    return render(*scene, *integ, o).image.rgb;
}

void expectRepeatable(const char* integrator, const char* sampler) {
    auto a = renderImage(integrator, sampler, 1, 3), b = renderImage(integrator, sampler, 2, 3),
         c = renderImage(integrator, sampler, 2, 3), d = renderImage(integrator, sampler, 2, 4);
    EXPECT_EQ(a, b) << integrator << " " << sampler;
    EXPECT_EQ(b, c) << integrator << " " << sampler;
    EXPECT_NE(b, d) << integrator << " " << sampler << ": the seed must change the image";
}

}  // namespace

TEST(Determinism, SameSeedSameImageAcrossThreadCounts) {
    for (const std::string& sampler : samplerNames()) expectRepeatable("path", sampler.c_str());
}

// Light tracing and BDPT splat onto the film from every thread; the fixed-point splat
// accumulation makes the sum independent of the order, so these are bit-identical across
// thread counts as well.
TEST(Determinism, SplattingIntegratorsAreBitIdentical) {
    for (const char* integrator : {"light", "bdpt"}) expectRepeatable(integrator, "sobol");
}
