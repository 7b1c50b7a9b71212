// Shape "curve" in whole renders, against exact expected images: black curves in front of a
// white sky hide exactly the fraction of the image they cover, and white curves in a white
// furnace reflect exactly 1 with direct lighting (any shadow ray a curve cast on itself would show
// as a darker image), for path tracing, light tracing and BDPT. Also how bad curve parameters
// are reported.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "render/scene.h"
#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

// |mean - exact| < 4 sigma, sigma measured from the pixels' spread (every pixel has the same
// expectation in the scenes below), and small enough to tell the alternatives apart.
void expectMean(const RegionStats& r, double exact, const std::string& what) {
    for (int c = 0; c < 3; ++c) {
        std::printf("  %s channel %d: %.5f +- %.5f, exact %.5f, %+.2f sigma\n", what.c_str(), c, r.mean[c], r.stdErr[c],
                    exact, (r.mean[c] - exact) / std::max(r.stdErr[c], 1e-12));
        EXPECT_NEAR(r.mean[c], exact, 4 * r.stdErr[c] + 1e-6) << what << ", channel " << c;
        EXPECT_LT(r.stdErr[c], 0.01 * exact) << what << ": too noisy to test";
    }
}

// One straight curve along y (x = x0, beyond the top and bottom of the view) of each type.
std::string verticalCurve(const std::string& type, float x0, float width) {
    std::string x = std::to_string(x0), w = std::to_string(width);
    return "Shape \"curve\" \"string type\" \"" + type + "\" \"float width\" [ " + w + " ] \"point3 P\" [ " + x +
           " -1.5 0  " + x + " -0.5 0  " + x + " 0.5 0  " + x + " 1.5 0 ]" +
           (type == "ribbon" ? " \"normal N\" [ 0 0 -1  0 0 -1 ]" : "") + "\n";
}

}  // namespace

// An orthographic view of the square [-1, 1]^2 on 32 x 32 pixels; one black curve of width
// 0.4 pixel centred in each pixel column, so every pixel's expected value is the uncovered
// fraction 0.6 of the white sky behind, for flat, ribbon (facing the camera) and cylinder curves.
TEST(CurveRender, BlackCurvesHideTheFractionTheyCover) {
    const int n = 32;
    const float pixel = 2.0f / n;
    for (const char* type : {"flat", "ribbon", "cylinder"}) {
        std::string scene = R"(
            LookAt 0 0 -5  0 0 0  0 1 0
            Camera "orthographic"
            Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
            PixelFilter "box"
            Sampler "independent"
            Integrator "path" "integer maxdepth" [ 1 ]
            WorldBegin
            LightSource "infinite" "rgb L" [ 1 1 1 ]
            Material "diffuse" "rgb reflectance" [ 0 0 0 ]
        )";
        for (int i = 0; i < n; ++i) scene += verticalCurve(type, -1 + (i + 0.5f) * pixel, 0.4f * pixel);
        RenderResult r = renderString(scene, 256);
        expectMean(wholeImage(r.image), 0.6, std::string(type));
    }
}

// A white (reflectance 1) diffuse curve inside a sphere that emits 1 everywhere inwards,
// direct lighting only (maxdepth 1): every point of a surface that does not see itself
// reflects exactly 1, like the emitter around it, so the whole image is 1 in expectation.
// Straight curves (a tube is convex, a flat curve and a ribbon with one normal are planar
// strips) seen obliquely, in perspective. (An enclosing emitter rather than a sky, as light
// tracing does not image infinite lights.) Flat and cylinder curves turn to face each ray, so
// the light and camera ends of a joined path see differently oriented strips: only path
// tracing, which builds every path from the camera, is consistent on them with a material
// other than hair, whose adjoint allows for it (as in pbrt-v4).
TEST(CurveRender, WhiteCurvesInAWhiteFurnaceAreWhite) {
    for (const char* type : {"flat", "ribbon", "cylinder"}) {
        std::string scene = std::string(R"(
            LookAt 0 0 -5  0 0 0  0 1 0
            Camera "perspective" "float fov" [ 30 ]
            Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
            PixelFilter "box"
            Sampler "independent"
            Integrator "path" "integer maxdepth" [ 1 ]
            WorldBegin
            AttributeBegin
              Material "diffuse" "rgb reflectance" [ 0 0 0 ]
              AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "bool twosided" true
              Shape "sphere" "float radius" [ 8 ]
            AttributeEnd
            Material "diffuse" "rgb reflectance" [ 1 1 1 ]
            Shape "curve" "string type" ")") + type +
                            R"(" "float width0" [ 0.3 ] "float width1" [ 0.6 ]
                "point3 P" [ -1.5 -1 1  -0.5 -0.3333333 0.5  0.5 0.3333333 0  1.5 1 -0.5 ]
                "normal N" [ 0 0 -1  0 0 -1 ]
        )";
        const bool facesRay = std::string(type) != "ribbon";
        if (std::string(type) != "ribbon") scene.erase(scene.find("\"normal N\""));
        for (const char* integrator : {"path", "light", "bdpt"}) {
            if (facesRay && std::string(integrator) != "path") continue;
            // Light tracing rarely finds the curve from the emitter: more samples.
            const int spp = std::string(integrator) == "light" ? 4096 : 256;
            RenderResult r = renderString(scene, spp, 7, 0, integrator);
            expectMean(wholeImage(r.image), 1.0, std::string(type) + " " + integrator);
        }
    }
}

// pbrt-v4 reports bad curve parameters and skips the curve (a warning here); an area light on
// a curve is an error (pbrt-v4 cannot sample curves).
TEST(CurveRender, BadParametersAreReported) {
    setWarningsQuiet(true);
    const std::string head = "LookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
    const char* skipped[] = {
        "Shape \"curve\" \"integer degree\" [ 4 ] \"point3 P\" [ -1 0 0  0 0 0  1 0 0  2 0 0  3 0 0 ]",
        "Shape \"curve\" \"point3 P\" [ -1 0 0  0 0 0  1 0 0  2 0 0  3 0 0 ]",  // 4 + 3n points needed
        "Shape \"curve\" \"string basis\" \"hermite\" \"point3 P\" [ -1 0 0  0 0 0  1 0 0  2 0 0 ]",
        "Shape \"curve\" \"string type\" \"ribbon\" \"point3 P\" [ -1 0 0  0 0 0  1 0 0  2 0 0 ]",  // no N
        "Shape \"curve\" \"string type\" \"ribbon\" \"normal N\" [ 0 0 1 ] \"point3 P\" [ -1 0 0  0 0 0  1 0 0  2 0 0 ]",
    };
    for (const char* shape : skipped) {
        int before = warningCount();
        auto scene = buildScene(parseSceneString(head + shape + "\n", ".", "<test>"));
        SurfaceInteraction si;
        EXPECT_FALSE(scene->intersect(Ray{{0.5f, 0, -5}, {0, 0, 1}, 1e30f}, si)) << shape;
        EXPECT_EQ(warningCount(), before + 1) << shape;
    }
    // An unknown type warns and becomes a tube; N on a non-ribbon curve warns and is ignored.
    for (const char* shape : {"Shape \"curve\" \"string type\" \"tube\" \"point3 P\" [ -1 0 0  0 0 0  1 0 0  2 0 0 ]",
                              "Shape \"curve\" \"normal N\" [ 0 0 1  0 0 1 ] \"point3 P\" [ -1 0 0  0 0 0  1 0 0  2 0 0 ]"}) {
        int before = warningCount();
        auto scene = buildScene(parseSceneString(head + shape + "\n", ".", "<test>"));
        SurfaceInteraction si;
        EXPECT_TRUE(scene->intersect(Ray{{0.5f, 0, -5}, {0, 0, 1}, 1e30f}, si)) << shape;
        EXPECT_EQ(warningCount(), before + 1) << shape;
    }
    try {
        buildScene(parseSceneString(head + "AreaLightSource \"diffuse\"\n"
                                           "Shape \"curve\" \"point3 P\" [ -1 0 0  0 0 0  1 0 0  2 0 0 ]\n",
                                    ".", "<test>"));
        ADD_FAILURE() << "an emitting curve was accepted";
    } catch (const InputError& e) {
        std::printf("  %s\n", e.what());
        EXPECT_NE(std::string(e.what()).find("<test>:5:1: error: curve: area lights"), std::string::npos) << e.what();
    }
}
