// Texture mappings end to end: a planar-mapped checkerboard (its own transform captured at
// the Texture directive) as a diffuse reflectance under a uniform white sky. Each pixel's
// expected value is its check's reflectance exactly (rho/pi times the sky's irradiance pi),
// so every check's block of pixels must average to it within 4 sigma.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

// An orthographic camera sees x, y in [-1, 1] on the plane z = 3, 32 x 32 pixels: pixel
// (px, py) centres on x = -1 + (px + 0.5) / 16, y = 1 - (py + 0.5) / 16. The texture's CTM
// translates by 0.5 in x, so q = p - (0.5, 0, 0); with v1 = (2, 0, 0), v2 = (0, 1, 0) and
// udelta 0.5: s = 2x - 0.5, t = y. Check edges (s or t integer) fall on pixel edges: x =
// -0.75, -0.25, 0.25, 0.75 (px = 4, 12, 20, 28) and y = 0 (py = 16).
TEST(TextureMappingRender, PlanarCheckerboardBlocks) {
    const char* scene = R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "orthographic"
        Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
        LightSource "infinite" "rgb L" [ 1 1 1 ]
        AttributeBegin
          Translate 0.5 0 0
          Texture "checks" "spectrum" "checkerboard" "string mapping" "planar"
              "vector3 v1" [ 2 0 0 ] "vector3 v2" [ 0 1 0 ] "float udelta" [ 0.5 ]
              "rgb tex1" [ 0.8 0.8 0.8 ] "rgb tex2" [ 0.2 0.2 0.2 ]
        AttributeEnd
        Material "diffuse" "texture reflectance" "checks"
        Shape "trianglemesh" "point3 P" [ -4 -4 3  4 -4 3  4 4 3  -4 4 3 ] "integer indices" [ 0 1 2  0 2 3 ]
    )";
    RenderResult r = renderString(scene, 16);
    const int xEdges[] = {0, 4, 12, 20, 28, 32}, yEdges[] = {0, 16, 32};
    for (int bx = 0; bx < 5; ++bx)
        for (int by = 0; by < 2; ++by) {
            const int x0 = xEdges[bx], x1 = xEdges[bx + 1], y0 = yEdges[by], y1 = yEdges[by + 1];
            // The block's centre in world space and its check from the mapping's definition.
            double x = -1 + 0.5 * (x0 + x1) / 16.0, y = 1 - 0.5 * (y0 + y1) / 16.0;
            double s = 0.5 + 2 * (x - 0.5), t = y;
            bool even = (long(std::floor(s)) + long(std::floor(t))) % 2 == 0;
            double expected = even ? 0.8 : 0.2;
            RegionStats st = regionStats(r.image, x0, x1, y0, y1);
            std::printf("  block x [%2d,%2d) y [%2d,%2d): %.4f +- %.4f, expected %.1f (%+.2f sigma)\n", x0, x1, y0, y1, st.mean[1],
                        st.stdErr[1], expected, (st.mean[1] - expected) / std::max(st.stdErr[1], 1e-12));
            EXPECT_NEAR(st.mean[1], expected, 4 * st.stdErr[1] + 1e-6) << "block " << bx << "," << by;
            EXPECT_LT(st.stdErr[1], 0.03) << "too noisy to tell 0.8 from 0.2";
        }
}
