// The render's own error estimate (per-pixel variance of the mean) agrees with the error
// actually observed, and falls as 1/N.
#include <gtest/gtest.h>

#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

// Every pixel sees the same expected value (inside a closed emitting sphere), so the spread
// of pixel values across the image is an independent measurement of the per-pixel variance.
const char* kFurnace = R"(
    LookAt 0 0 0  0 0 1  0 1 0
    Camera "perspective" "float fov" [ 60 ]
    Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
    PixelFilter "box"
    Sampler "independent"
    Integrator "path" "integer maxdepth" [ 5 ]
    WorldBegin
    AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
    Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
    ReverseOrientation
    Shape "sphere" "float radius" [ 1 ]
)";

}  // namespace

TEST(ErrorEstimate, MatchesObservedSpreadAndFallsAsOneOverN) {
    RenderResult a = renderString(kFurnace, 16), b = renderString(kFurnace, 64);
    RegionStats s = wholeImage(a.image);
    // Observed variance of a pixel's luminance estimate (all channels equal here).
    double observed = s.stdErr[1] * s.stdErr[1] * s.n;
    // With n = 1024 pixels the observed variance itself has a relative spread of about
    // sqrt(2/n) ~ 4.4% (more for the heavy-tailed path contributions): allow 20%.
    EXPECT_NEAR(a.error.meanVariance, observed, 0.2 * observed);
    EXPECT_NEAR(a.error.meanVariance / b.error.meanVariance, 4.0, 0.6);
    EXPECT_GT(a.efficiency, 0.0);
}
