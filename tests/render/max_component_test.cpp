// Film "maxcomponentvalue" m: every camera sample, every light-path splat measured as a
// camera sample of its pixel, and every Markov chain's splat as it is given, whose largest
// component in the sensor's space (X, Y, Z for the cie1931 sensor, as pbrt-v4 measures it)
// exceeds m is scaled down to m, hue kept. RGB mode: the values are exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

// A tiny one-sided emitter of radiance (1000, 500, 250) facing the camera, alone in the dark,
// covering the central pixels fully.
std::string tinyBrightEmitter(const std::string& filmExtra) {
    return R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 8 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ] )" + filmExtra + R"(
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
        Material "diffuse" "rgb reflectance" [ 0 0 0 ]
        AreaLightSource "diffuse" "rgb L" [ 1000 500 250 ]
        Shape "trianglemesh" "point3 P" [ -0.1 -0.1 10  0.1 -0.1 10  0.1 0.1 10  -0.1 0.1 10 ]
            "integer indices" [ 0 2 1  0 3 2 ]
    )";
}

// A colour of the emitter's hue (1000, 500, 250) whose largest XYZ component is m.
void expectClampedHue(Spectrum c, double m, double tol) {
    EXPECT_NEAR(largestXYZ(c), m, tol * m);
    EXPECT_NEAR(c.g / c.r, 0.5, 1e-4);
    EXPECT_NEAR(c.b / c.r, 0.25, 1e-4);
}

}  // namespace

// Path tracing: a pixel the emitter covers gets (1000, 500, 250) from every sample, clamped so
// that its X (the largest of X, Y, Z here: 636) is m, not its R: (3.14, 1.57, 0.79) for m = 2.
TEST(MaxComponentValue, ClampsEachCameraSample) {
    RenderResult plain = renderString(tinyBrightEmitter(""), 16);
    RenderResult clamped = renderString(tinyBrightEmitter("\"float maxcomponentvalue\" [ 2 ]"), 16);
    for (int p : {11, 12}) {
        Spectrum a = plain.image.get(p, p), b = clamped.image.get(p, p);
        std::printf("  pixel %d: unclamped (%g %g %g), clamped (%g %g %g)\n", p, a.r, a.g, a.b, b.r, b.g, b.b);
        EXPECT_NEAR(a.r, 1000, 1e-2);
        expectClampedHue(b, 2, 1e-3);
    }
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) EXPECT_LE(largestXYZ(clamped.image.get(x, y)), 2 * 1.001) << x << "," << y;
}

// Light tracing: each light path splats once (from the emitter straight through the lens), a
// value far above m, clamped to m in camera-sample units; with one light path per camera
// sample the image's mean largest XYZ component is then exactly m (and the hue is kept). Unclamped it is the
// emitter's radiance times its share of the view.
TEST(MaxComponentValue, ClampsEachSplatInCameraSampleUnits) {
    RenderResult plain = renderString(tinyBrightEmitter(""), 16, 7, 0, "light");
    RenderResult clamped = renderString(tinyBrightEmitter("\"float maxcomponentvalue\" [ 2 ]"), 16, 7, 0, "light");
    RegionStats a = wholeImage(plain.image), b = wholeImage(clamped.image);
    std::printf("  image mean: unclamped (%g %g %g), clamped (%.6f %.6f %.6f)\n", a.mean[0], a.mean[1], a.mean[2],
                b.mean[0], b.mean[1], b.mean[2]);
    EXPECT_GT(a.mean[0], 10.0);  // 1000 x the emitter's share of the view, 0.0204
    expectClampedHue(Spectrum(float(b.mean[0]), float(b.mean[1]), float(b.mean[2])), 2, 1e-3);
}

// Metropolis (pssmlt, mmlt, mlt): each splat, the sample's contribution over its target (its
// luminance) times its expected-value weight, is clamped as it is given, the imaging ratio
// included (pbrt-v4's MLTIntegrator, with the target in the sensor's units). Here every path
// is the emitter seen directly, whose contribution is the same wherever it is hit: a proposal
// is accepted with probability 1 or 0, so every splat has weight 1, and its largest component
// is the emitter colour's X / Y. A clamp m below that scales the whole image by
// m / (ratio X / Y), exactly; one above it leaves the image bit for bit.
TEST(MaxComponentValue, ClampsEachChainSplat) {
    const Spectrum colour(1000, 500, 250);
    const double xOverY = largestXYZ(colour) / colour.luminance();
    for (const char* integrator : {"pssmlt", "mmlt", "mlt"})
        for (const double iso : {100.0, 200.0}) {
            const double ratio = iso / 100;
            const std::string film = "\"float iso\" [ " + std::to_string(iso) + " ] ";
            auto render = [&](const std::string& clamp) {
                RenderOptions opts;
                opts.spp = 4;
                opts.seed = 3;
                return renderWith(tinyBrightEmitter(film + clamp), opts, integrator, false).image;
            };
            const Image plain = render("");
            const Image above = render("\"float maxcomponentvalue\" [ " + std::to_string(1.001 * ratio * xOverY) + " ]");
            const Image clamped = render("\"float maxcomponentvalue\" [ 0.5 ]");
            EXPECT_EQ(comparePixels(above, plain).differ, 0) << integrator << " iso " << iso;
            const double scale = 0.5 / (ratio * xOverY);
            double worst = 0, lit = 0;
            for (int y = 0; y < plain.height; ++y)
                for (int x = 0; x < plain.width; ++x) {
                    const Spectrum p = plain.get(x, y), c = clamped.get(x, y);
                    if (p.r <= 0) continue;
                    lit += 1;
                    for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::fabs(c[ch] / (p[ch] * scale) - 1));
                }
            std::printf("  %s, iso %g: %g lit pixels, clamped / unclamped within %.2g of %.4f\n", integrator, iso, lit,
                        worst, scale);
            EXPECT_GT(lit, 4);
            EXPECT_LT(worst, 1e-4) << integrator << " iso " << iso;
        }
}

TEST(MaxComponentValue, MustBePositive) {
    setWarningsQuiet(true);
    for (const char* v : {"0", "-1"}) {
        SceneDescription desc =
            parseSceneString(tinyBrightEmitter(std::string("\"float maxcomponentvalue\" [ ") + v + " ]"), ".", "<test>");
        try {
            buildScene(desc);
            ADD_FAILURE() << "maxcomponentvalue " << v << " accepted";
        } catch (const InputError& e) {
            std::printf("  %s\n", e.what());
            EXPECT_NE(std::string(e.what()).find("maxcomponentvalue"), std::string::npos);
            EXPECT_NE(std::string(e.what()).find("<test>:4:"), std::string::npos) << "location of the parameter";
        }
    }
}
