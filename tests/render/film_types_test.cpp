// pbrt-v4's "gbuffer" and "spectral" films are rendered as its "rgb" film (with a warning,
// tests/app/bad_inputs_test.cpp): the same image, sample for sample, whatever their own
// parameters say, and "maxcomponentvalue" and the other rgb parameters still apply.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

std::string sceneWithFilm(const std::string& film) {
    return R"(
        LookAt 0 1 -4  0 0.5 0  0 1 0
        Camera "perspective" "float fov" [ 40 ]
        Film )" + film + R"( "integer xresolution" [ 24 ] "integer yresolution" [ 16 ] "float maxcomponentvalue" [ 3 ]
        Sampler "independent"
        PixelFilter "box"
        WorldBegin
        LightSource "infinite" "rgb L" [ 0.3 0.4 0.5 ]
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 20 10 5 ]
          Translate 0.8 1.2 0
          Shape "sphere" "float radius" [ 0.2 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.6 0.5 0.4 ]
        Shape "sphere" "float radius" [ 0.5 ]
        Shape "trianglemesh" "point3 P" [ -3 0 -3  3 0 -3  3 0 3  -3 0 3 ] "integer indices" [ 0 1 2  0 2 3 ]
    )";
}

}  // namespace

TEST(FilmTypes, GbufferAndSpectralFilmsRenderTheRgbImage) {
    const RenderResult rgb = renderString(sceneWithFilm("\"rgb\""), 8, 3, 1);
    const RenderResult gbuffer = renderString(sceneWithFilm("\"gbuffer\" \"string coordinatesystem\" \"world\""), 8, 3, 1);
    const RenderResult spectral =
        renderString(sceneWithFilm("\"spectral\" \"integer nbuckets\" [ 4 ] \"float lambdamax\" [ 700 ]"), 8, 3, 1);
    ASSERT_EQ(gbuffer.image.width, 24);
    ASSERT_EQ(gbuffer.image.height, 16);
    PixelComparison g = comparePixels(gbuffer.image, rgb.image), s = comparePixels(spectral.image, rgb.image);
    EXPECT_EQ(g.differ, 0);
    EXPECT_EQ(s.differ, 0);
    EXPECT_EQ(g.nonFinite, 0);
    // The clamp applies to every film type: no pixel's largest X, Y, Z above 3 (box filter:
    // averages of clamped samples).
    double largest = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 24; ++x) largest = std::max(largest, largestXYZ(gbuffer.image.get(x, y)));
    EXPECT_GT(largest, 1.0);  // the emitter is in view
    EXPECT_LE(largest, 3.0 * 1.001);
}
