// Alpha cut-outs ("float alpha" / "texture alpha"): in expectation a surface of alpha a blocks
// a fraction a of the rays that reach it, for camera rays, shadow rays and light-path
// connections alike, on every shape type and inside instances; a cut-out emitter emits from
// the fraction a of its points for every integrator. Black surfaces in front of a white emitter
// give exact expected images.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "geometry/alpha_mask.h"
#include "render_helpers.h"
#include "spectral_answer.h"

using namespace ps;
using namespace ps::test;

namespace {

// |mean - exact| < 4 sigma (sigma measured from the pixels' spread) in every channel, with
// sigma small enough (< 1.5% of exact) that the tests below can tell their alternatives apart.
void expectMean(const RegionStats& r, double exact, const char* what) {
    for (int c = 0; c < 3; ++c) {
        std::printf("  %s channel %d: %.5f +- %.5f, exact %.5f, %+.2f sigma\n", what, c, r.mean[c], r.stdErr[c], exact,
                    (r.mean[c] - exact) / std::max(r.stdErr[c], 1e-12));
        EXPECT_NEAR(r.mean[c], exact, 4 * r.stdErr[c] + 1e-5) << what << ", channel " << c;
        EXPECT_LT(r.stdErr[c], 0.015 * exact) << what << ": too noisy to test";
    }
}

// A white one-sided emitter (L = 1) at z = 10 facing a camera at the origin looking along +z,
// black material throughout; `blockers` go in between. Every pixel sees the emitter.
std::string emitterBehind(const std::string& blockers, int res = 24) {
    return R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 8 ]
        Film "rgb" "integer xresolution" [ )" + std::to_string(res) + R"( ] "integer yresolution" [ )" +
           std::to_string(res) + R"( ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 2 ]
        WorldBegin
        Material "diffuse" "rgb reflectance" [ 0 0 0 ]
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Shape "trianglemesh" "point3 P" [ -1 -1 10  1 -1 10  1 1 10  -1 1 10 ]
              "integer indices" [ 0 2 1  0 3 2 ]
        AttributeEnd
    )" + blockers;
}

// A black square of the given alpha parameter at depth z (covers the view for z <= 9).
std::string square(double z, const std::string& alpha) {
    std::string zs = std::to_string(z);
    return "Shape \"trianglemesh\" " + alpha + " \"point3 P\" [ -1 -1 " + zs + "  1 -1 " + zs + "  1 1 " + zs +
           "  -1 1 " + zs + " ] \"integer indices\" [ 0 1 2  0 2 3 ]\n";
}

const char* kIntegrators[] = {"path", "light", "bdpt"};

}  // namespace

// Camera rays (path), connections from the emitter to the lens (light) and both (bdpt) pass a
// half-transparent square half the time: the image is 0.5 exactly in expectation.
TEST(Alpha, HalfTransparentSquareTransmitsHalf) {
    std::string scene = emitterBehind(square(3, "\"float alpha\" [ 0.5 ]"));
    for (const char* integrator : kIntegrators) {
        RenderResult r = renderString(scene, 512, 7, 0, integrator);
        expectMean(wholeImage(r.image), 0.5, integrator);
    }
}

// Two cut-out squares along every ray decide independently: 0.6 * 0.3 of the light passes.
TEST(Alpha, TwoCutOutsAlongOneRayAreIndependent) {
    std::string scene = emitterBehind(square(3, "\"float alpha\" [ 0.4 ]") + square(5, "\"float alpha\" [ 0.7 ]"));
    for (const char* integrator : kIntegrators) {
        RenderResult r = renderString(scene, 512, 7, 0, integrator);
        expectMean(wholeImage(r.image), 0.6 * 0.3, integrator);
    }
}

// Alpha 0 removes a shape exactly: every sample sees the emitter. In RGB mode that is every
// pixel 1; in spectral mode, where each pixel carries its wavelengths' noise, every pixel is
// bit for bit the emitter's alone, and the image mean is the emission through the sensor.
TEST(Alpha, AlphaZeroIsInvisible) {
    const bool spectral = defaultSpectral();
    std::string scene = emitterBehind(square(3, "\"float alpha\" [ 0 ]") +
                                      "Shape \"sphere\" \"float radius\" [ 1 ] \"float alpha\" [ 0 ]\n");
    RenderResult r = renderString(scene, spectral ? 64 : 4);
    if (spectral) {
        EXPECT_EQ(comparePixels(r.image, renderString(emitterBehind(""), 64).image).differ, 0);
        expectSpectralMean(wholeImage(r.image), exactPixel(true, itself, emission({1, 1, 1})));
        return;
    }
    for (int y = 0; y < r.image.height; ++y)
        for (int x = 0; x < r.image.width; ++x) ASSERT_NEAR(r.image.get(x, y).g, 1.0f, 1e-5f) << x << "," << y;
}

// A sphere of alpha 0.5 filling the view: each ray crosses its near and far side (the far side
// found after the near one is cut out, inside Embree's user-geometry callback), each kept
// with probability 1/2, so 1/4 of the light passes. A disk and a cylinder (its wall crossed
// twice as well) of alpha 0.25 in front of it multiply in 0.75 and 0.75^2.
TEST(Alpha, QuadricsAreCutOutOnEachCrossing) {
    std::string sphere = emitterBehind(R"(
        AttributeBegin
          Translate 0 0 5
          Shape "sphere" "float radius" [ 2 ] "float alpha" [ 0.5 ]
        AttributeEnd)");
    for (const char* integrator : kIntegrators) {
        RenderResult r = renderString(sphere, 512, 7, 0, integrator);
        expectMean(wholeImage(r.image), 0.25, integrator);
    }
    std::string three = emitterBehind(R"(
        AttributeBegin
          Translate 0 0 5
          Shape "sphere" "float radius" [ 2 ] "float alpha" [ 0.5 ]
        AttributeEnd
        Shape "disk" "float height" [ 2 ] "float radius" [ 1 ] "float alpha" [ 0.25 ]
        AttributeBegin
          Translate 0 0 1.5
          Rotate 90 0 1 0
          Shape "cylinder" "float radius" [ 1 ] "float zmin" [ -1 ] "float zmax" [ 1 ] "float alpha" [ 0.25 ]
        AttributeEnd)");
    RenderResult r = renderString(three, 512, 7, 0, "path");
    expectMean(wholeImage(r.image), 0.25 * 0.75 * 0.5625, "path, sphere+disk+cylinder");
}

// Cut-outs inside an instance (the filter sees the ray in the prototype's space): two
// instances of one square of alpha 0.5 pass 1/4.
TEST(Alpha, InstancedCutOuts) {
    std::string scene = emitterBehind("ObjectBegin \"leaf\"\n" + square(0, "\"float alpha\" [ 0.5 ]") +
                                      "ObjectEnd\n"
                                      "AttributeBegin Translate 0 0 3 ObjectInstance \"leaf\" AttributeEnd\n"
                                      "AttributeBegin Translate 0 0 6 ObjectInstance \"leaf\" AttributeEnd\n");
    for (const char* integrator : kIntegrators) {
        RenderResult r = renderString(scene, 512, 7, 0, integrator);
        expectMean(wholeImage(r.image), 0.25, integrator);
    }
}

// "texture alpha": a checkerboard of alpha 1 and 0.25 over a black square seen by an
// orthographic camera, 8x8 pixels per check. The test runs at the hit's uv (the mesh's "uv",
// as shading interpolates it): opaque checks are exactly black, the others pass 0.75 in
// expectation. A wrong uv (flipped v, default triangle uv) swaps or mixes the checks.
TEST(Alpha, CheckerTextureAlphaFollowsTheMeshUV) {
    const char* scene = R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "orthographic"
        Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
        Material "diffuse" "rgb reflectance" [ 0 0 0 ]
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Shape "trianglemesh" "point3 P" [ -2 -2 10  2 -2 10  2 2 10  -2 2 10 ]
              "integer indices" [ 0 2 1  0 3 2 ]
        AttributeEnd
        Texture "checks" "float" "checkerboard" "float uscale" [ 4 ] "float vscale" [ 4 ]
            "float tex1" [ 1 ] "float tex2" [ 0.25 ]
        Shape "trianglemesh" "texture alpha" "checks"
            "point3 P" [ -1 -1 3  1 -1 3  1 1 3  -1 1 3 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]
            "integer indices" [ 0 1 2  0 2 3 ]
    )";
    RenderResult r = renderString(scene, 256);
    // Pixel (x, y) sees u = (x + 0.5) / 32 and v = 1 - (y + 0.5) / 32 (raster y points down), so
    // check (x / 8, 3 - y / 8): alpha 1 where those indices have equal parity.
    double s = 0, s2 = 0;
    int n = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            float v = r.image.get(x, y).g;
            if ((x / 8 + y / 8) % 2 == 1) {
                ASSERT_EQ(v, 0.0f) << "opaque check at pixel " << x << "," << y;
            } else {
                s += v;
                s2 += double(v) * v;
                ++n;
            }
        }
    RegionStats cut;
    double mean = s / n, stdErr = std::sqrt((s2 / n - mean * mean) / (n - 1));
    for (int c = 0; c < 3; ++c) {
        cut.mean[c] = mean;
        cut.stdErr[c] = stdErr;
    }
    expectMean(cut, 0.75, "alpha-0.25 checks");
}

// Shadow rays: a black occluder of alpha 0.5 (a disk: user geometry; a square: Embree's
// occlusion filter) between a distant light (irradiance 1) and a diffuse floor (0.5) halves
// the floor's radiance 0.5 / pi in expectation.
TEST(Alpha, HalfTransparentOccluderCastsHalfAShadow) {
    const std::string base = R"(
        LookAt 0 0.5 0  0 0 0  0 0 1
        Camera "perspective" "float fov" [ 10 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
        LightSource "distant" "point3 from" [ 0 1 0 ] "point3 to" [ 0 0 0 ] "rgb L" [ 1 1 1 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "trianglemesh" "point3 P" [ -20 0 -20  20 0 -20  20 0 20  -20 0 20 ]
            "integer indices" [ 0 1 2  0 2 3 ]
        Material "diffuse" "rgb reflectance" [ 0 0 0 ]
    )";
    const std::string disk = R"(
        AttributeBegin
          Translate 0 1 0
          Rotate -90 1 0 0
          Shape "disk" "float radius" [ 20 ] "float alpha" [ 0.5 ]
        AttributeEnd)";
    const std::string quad = R"(
        Shape "trianglemesh" "float alpha" [ 0.5 ] "point3 P" [ -20 1 -20  20 1 -20  20 1 20  -20 1 20 ]
            "integer indices" [ 0 1 2  0 2 3 ])";
    for (const std::string* occluder : {&disk, &quad})
        for (const char* integrator : {"path", "bdpt"}) {
            RenderResult r = renderString(base + *occluder, 512, 7, 0, integrator);
            expectMean(wholeImage(r.image), 0.25 / M_PI, (std::string(integrator) + (occluder == &disk ? ", disk" : ", square")).c_str());
        }
}

namespace {

// Irradiance below the centre of a parallel rectangle of radiance 1, 2a x 2b at height h,
// over pi: four corner form factors F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + (X<->Y)].
double rectangleFormFactor(double a, double b, double h) {
    double X = a / h, Y = b / h;
    double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    return 4 * (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * M_PI);
}

// A diffuse floor (0.5) under a 2 x 1 emitter (L = 1) at height 1 with the given alpha, seen in
// a tiny spot by a camera between them.
std::string floorUnderLight(const std::string& alpha) {
    return R"(
        LookAt 0 0.5 0   0 0 0   0 0 1
        Camera "perspective" "float fov" [ 0.5 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
        AttributeBegin
          Material "diffuse" "rgb reflectance" [ 0 0 0 ]
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Shape "bilinearmesh" )" + alpha + R"( "point3 P" [ -1 1 -0.5   1 1 -0.5   -1 1 0.5   1 1 0.5 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "trianglemesh" "point3 P" [ -20 0 -20  20 0 -20  20 0 20  -20 0 20 ]
            "integer indices" [ 0 1 2  0 2 3 ]
    )";
}

}  // namespace

// A cut-out emitter: a point is present or cut out for rays and emission alike (the test of
// the point), so an emitter of alpha 0.5 seen directly is half as bright for every integrator
// (camera rays hitting it, light paths leaving it, and their combinations), and so is the
// light it casts, found by light sampling and by BSDF sampling alike.
TEST(Alpha, CutOutEmitterEmitsFromItsPresentHalf) {
    std::string direct = emitterBehind("");
    const std::string opaque = "Shape \"trianglemesh\" \"point3 P\"";
    direct.replace(direct.find(opaque), opaque.size(), "Shape \"trianglemesh\" \"float alpha\" [ 0.5 ] \"point3 P\"");
    for (const char* integrator : kIntegrators) {
        RenderResult r = renderString(direct, 512, 7, 0, integrator);
        expectMean(wholeImage(r.image), 0.5, (std::string(integrator) + ", seen").c_str());
    }
    const double lit = 0.5 * rectangleFormFactor(1.0, 0.5, 1.0);  // floor radiance under the opaque light
    for (const char* integrator : {"path", "bdpt"}) {
        RenderResult r = renderString(floorUnderLight("\"float alpha\" [ 0.5 ]"), 256, 7, 0, integrator);
        expectMean(wholeImage(r.image), 0.5 * lit, (std::string(integrator) + ", floor").c_str());
    }
}

// The cut-out emitter's own sampling: light-path origins (sampleLe) and light samples
// (sampleLi) land on present points only, a fraction alpha of them, and emit there.
TEST(Alpha, CutOutEmitterSamplesPresentPointsOnly) {
    setWarningsQuiet(true);
    std::string text = emitterBehind("");
    const std::string opaque = "Shape \"trianglemesh\" \"point3 P\"";
    text.replace(text.find(opaque), opaque.size(), "Shape \"trianglemesh\" \"float alpha\" [ 0.3 ] \"point3 P\"");
    auto scene = buildScene(parseSceneString(text, ".", "<test>"));
    ASSERT_EQ(scene->lights().size(), 2u);
    const int n = 20000;
    int le = 0, li = 0, leEmitting = 0, liEmitting = 0;
    for (int i = 0; i < n; ++i) {
        // Independent uniform numbers, hashed from i.
        const float key[2] = {float(i), 0.5f}, key2[2] = {float(i), 1.5f}, key3[2] = {float(i), 2.5f};
        Vec2 u(hashToUnit(key, 2), hashToUnit(key2, 2));
        Vec2 uDir(hashToUnit(key3, 2), 0.5f);
        const Light& light = *scene->lights()[size_t(i % 2)];
        if (auto s = light.sampleLe(u, uDir, nullptr)) {
            ++le;
            leEmitting += !light.L(s->ray.o, s->n, Vec2(), s->ray.d, nullptr).isBlack();
        }
        if (auto s = light.sampleLi(LightSampleContext{Vec3(0, 0, 0), Vec3(0, 0, 1)}, u)) {
            ++li;
            liEmitting += !s->L.isBlack();
        }
    }
    const double sigma = std::sqrt(0.3 * 0.7 / n);
    std::printf("  sampleLe kept %.4f, sampleLi kept %.4f, alpha 0.3, sigma %.4f\n", double(le) / n, double(li) / n, sigma);
    EXPECT_EQ(leEmitting, le) << "light-path origins on cut-out points";
    EXPECT_EQ(liEmitting, li);
    EXPECT_NEAR(double(le) / n, 0.3, 4 * sigma);
    EXPECT_NEAR(double(li) / n, 0.3, 4 * sigma);
}

// A constant alpha 0 emitter is invisible yet lights the scene fully through light sampling
// (pbrt-v4's invisible area light): the floor below it gets the opaque light's radiance.
// "texture alpha" naming a "constant" texture of value 0 is the same constant alpha.
TEST(Alpha, AlphaZeroEmitterIsAnInvisibleLight) {
    const double lit = 0.5 * rectangleFormFactor(1.0, 0.5, 1.0);
    const std::string zeroTexture = "WorldBegin\nTexture \"zero\" \"float\" \"constant\" \"float value\" [ 0 ]\n";
    auto withZeroTexture = [&](std::string scene) { return scene.replace(scene.find("WorldBegin"), 10, zeroTexture); };
    for (const char* alpha : {"\"float alpha\" [ 0 ]", "\"texture alpha\" \"zero\""}) {
        for (const char* integrator : {"path", "bdpt"}) {
            RenderResult r = renderString(withZeroTexture(floorUnderLight(alpha)), 64, 7, 0, integrator);
            expectMean(wholeImage(r.image), lit, (std::string(integrator) + ", floor, " + alpha).c_str());
        }
        // Seen directly it is not there.
        std::string direct = withZeroTexture(emitterBehind(""));
        const std::string opaque = "Shape \"trianglemesh\" \"point3 P\"";
        direct.replace(direct.find(opaque), opaque.size(), "Shape \"trianglemesh\" " + std::string(alpha) + " \"point3 P\"");
        for (const char* integrator : kIntegrators) {
            RenderResult r = renderString(direct, 4, 7, 0, integrator);
            EXPECT_EQ(wholeImage(r.image).mean[1], 0.0) << integrator << ", " << alpha;
        }
    }
}
