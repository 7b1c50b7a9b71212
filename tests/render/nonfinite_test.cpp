// Scenes built to provoke NaN and infinity (degenerate and needle triangles, zero-area
// lights, shading normals opposite to the geometry, eta = 1, roughness 0 and 1, a huge
// emitter): every integrator must still write only finite pixels, and what it had to
// guard against is counted, not hidden.
#include <gtest/gtest.h>

#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

const char* kProvoking = R"(
    LookAt 0 0.5 2.5  0 0.4 0  0 1 0
    Camera "perspective" "float fov" [ 40 ]
    Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
    Integrator "path" "integer maxdepth" [ 6 ]
    WorldBegin
    # A regular light, a zero-area light (collinear vertices) and a needle light.
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 5 5 5 ]
      Shape "bilinearmesh" "point3 P" [ -0.3 1.5 -0.3   0.3 1.5 -0.3   -0.3 1.5 0.3   0.3 1.5 0.3 ]
      Shape "trianglemesh" "point3 P" [ 0 1.4 0  0.5 1.4 0  1 1.4 0 ] "integer indices" [ 0 1 2 ]
      Shape "trianglemesh" "point3 P" [ -1 1.3 0  1 1.3 0  1 1.3 1e-7 ] "integer indices" [ 0 1 2 ]
    AttributeEnd
    # A tiny, very bright emitter far away.
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 1e6 1e6 1e6 ]
      Translate 0 40 -40
      Shape "sphere" "float radius" [ 0.001 ]
    AttributeEnd
    # Floor with shading normals pointing against its winding; degenerate triangles in it.
    Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
    Shape "trianglemesh" "point3 P" [ -2 0 2  2 0 2  2 0 -2  -2 0 -2  0 0 0 ]
        "normal N" [ 0 -1 0  0 -1 0  0 -1 0  0 -1 0  0 -1 0 ]
        "integer indices" [ 0 1 2  0 2 3  4 4 4  0 0 1 ]
    # Needle triangles and zero-length normals.
    Shape "trianglemesh" "point3 P" [ -0.5 0 0  0.5 0 0  0.5 1 1e-6 ] "normal N" [ 0 0 0  0 0 0  0 0 0 ]
        "integer indices" [ 0 1 2 ]
    AttributeBegin
      Material "dielectric" "float eta" [ 1 ]
      Translate -0.5 0.3 0
      Shape "sphere" "float radius" [ 0.25 ]
    AttributeEnd
    AttributeBegin
      Material "dielectric" "float eta" [ 1.5 ] "float roughness" [ 1 ]
      Translate 0.5 0.3 0
      Shape "sphere" "float radius" [ 0.25 ]
    AttributeEnd
    AttributeBegin
      Material "conductor" "float roughness" [ 0 ]
      Translate 0 0.3 -0.6
      Shape "sphere" "float radius" [ 0.25 ]
    AttributeEnd
    AttributeBegin
      Material "conductor" "float roughness" [ 1 ]
      Translate 0 0.3 0.6
      Shape "sphere" "float radius" [ 0.2 ]
    AttributeEnd
    AttributeBegin
      Material "coateddiffuse" "float roughness" [ 1 ] "rgb reflectance" [ 0.5 0.5 0.5 ]
      Translate 0.8 0.2 0.5
      Shape "sphere" "float radius" [ 0.15 ]
    AttributeEnd
)";

}  // namespace

TEST(NonFinite, ProvokingSceneGivesFinitePixelsWithEveryIntegrator) {
    for (const char* integrator : {"path", "light", "bdpt"}) {
        RenderResult r = renderString(kProvoking, 16, 3, 0, integrator);
        size_t bad = 0;
        for (float v : r.image.rgb) bad += !std::isfinite(v);
        EXPECT_EQ(bad, 0u) << integrator;
        std::printf("  %s: %llu non-finite values guarded at their source, %lld samples rejected by the film\n",
                    integrator, (unsigned long long)r.stats.guarded, r.rejectedSamples);
        RegionStats s = wholeImage(r.image);
        EXPECT_GT(s.mean[1], 0.0) << integrator << ": the scene must be lit";
    }
}

// An emitter so bright (1e30) that products along a path leave the float range: nothing
// non-finite may reach the image, and what was dropped is counted. (Light tracing's splats
// of it exceed the film's fixed-point range and are rejected, so its image stays dark.)
TEST(NonFinite, HugeEmitterIsGuardedAndCounted) {
    const char* scene = R"(
        LookAt 0 0.5 2.5  0 0.4 0  0 1 0
        Camera "perspective" "float fov" [ 40 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        Integrator "path" "integer maxdepth" [ 4 ]
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1e30 1e30 1e30 ]
          Translate 0 3 0
          Shape "sphere" "float radius" [ 0.01 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -2 0 2   2 0 2   -2 0 -2   2 0 -2 ]
    )";
    for (const char* integrator : {"path", "light", "bdpt"}) {
        RenderResult r = renderString(scene, 8, 3, 0, integrator);
        size_t bad = 0;
        for (float v : r.image.rgb) bad += !std::isfinite(v);
        EXPECT_EQ(bad, 0u) << integrator;
        std::printf("  %s: %llu guarded, %lld rejected\n", integrator, (unsigned long long)r.stats.guarded,
                    r.rejectedSamples);
        if (std::string(integrator) == "light") {
            EXPECT_GT(r.rejectedSamples + (long long)r.stats.guarded, 0);
        }
    }
}
