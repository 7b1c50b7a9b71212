// Scenes with closed-form answers; tolerances come from the measured standard error.
#include <gtest/gtest.h>

#include <cstdio>

#include "render_helpers.h"
#include "spectral_answer.h"

using namespace ps;
using namespace ps::test;

namespace {

// |mean - exact| < 4 sigma, plus a floor of 1e-4 relative for single-precision arithmetic
// (stratified sampling can push sigma below what float geometry resolves). Sigma must be under
// 0.5% of the value, so that a 2% error fails (4 sigma < 2%).
void expectWithin4Sigma(const RegionStats& r, const double expected[3], double maxRelStdErr = 0.005) {
    const double systematic = 1e-4;
    for (int c = 0; c < 3; ++c) {
        std::printf("  channel %d: %.6f +- %.6f (%.3f%%), exact %.6f, %+.2f sigma\n", c, r.mean[c], r.stdErr[c],
                    100 * r.stdErr[c] / expected[c], expected[c], (r.mean[c] - expected[c]) / std::max(r.stdErr[c], 1e-12));
        EXPECT_NEAR(r.mean[c], expected[c], 4 * r.stdErr[c] + systematic * expected[c] + 1e-7)
            << "channel " << c << ": mean " << r.mean[c] << " +- " << r.stdErr[c] << ", exact " << expected[c];
        // The test must be able to fail: the noise has to be small against the value.
        if (expected[c] > 0) {
            EXPECT_LT(r.stdErr[c], maxRelStdErr * expected[c]) << "channel " << c;
        }
    }
}

double product(double a, double b) { return a * b; }

// The grey diffuse surfaces below (albedo 0.5) lit by "rgb L" or "rgb I" `L` with the
// geometric factor g: rho g L, per channel or per wavelength.
std::array<double, 3> greyLitBy(double g, std::array<float, 3> L, bool spectral = defaultSpectral()) {
    return exactPixel(
        spectral, [g](double rho, double Le) { return rho * g * Le; }, reflectance({0.5f, 0.5f, 0.5f}), emission(L));
}

// The same lit by [ 2 3 4 ].
std::array<double, 3> greyLitBy234(double g, bool spectral = defaultSpectral()) { return greyLitBy(g, {2, 3, 4}, spectral); }

// Irradiance below the centre of a parallel rectangle of radiance L, 2a x 2b at height h:
// four corner form factors F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + (X<->Y)].
double cornerFormFactor(double a, double b, double h) {
    double X = a / h, Y = b / h;
    double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * M_PI);
}

// A diffuse plane under a rectangular light, seen in a tiny spot by a camera between them.
const char* kPlaneUnderRectangle = R"(
        LookAt 0 0.5 0   0 0 0   0 0 1
        Camera "perspective" "float fov" [ 0.5 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 2 3 4 ]
          Shape "bilinearmesh" "point3 P" [ -1 1 -0.5   1 1 -0.5   -1 1 0.5   1 1 0.5 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "trianglemesh" "point3 P" [ -20 0 -20  20 0 -20  20 0 20  -20 0 20 ]
            "integer indices" [ 0 1 2 0 2 3 ]
    )";

// The same plane under a point light.
const char* kPlaneUnderPoint = R"(
        LookAt 0 0.5 0   0 0 0   0 0 1
        Camera "perspective" "float fov" [ 0.5 ]
        Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 3 ]
        WorldBegin
        LightSource "point" "rgb I" [ 2 3 4 ] "point3 from" [ 0 2 0 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "trianglemesh" "point3 P" [ -20 0 -20  20 0 -20  20 0 20  -20 0 20 ]
            "integer indices" [ 0 1 2 0 2 3 ]
    )";

// A diffuse sphere filling the view under a uniform sky.
const char* kSphereUnderSky = R"(
        LookAt 0 0 5  0 0 0  0 1 0
        Camera "perspective" "float fov" [ 10 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 5 ]
        WorldBegin
        LightSource "infinite" "rgb L" [ 0.8 0.9 1.0 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.3 0.7 ]
        Shape "sphere" "float radius" [ 1 ]
    )";

// A Loop-subdivided cube (convex limit surface) filling the view under a uniform sky.
const char* kSubdividedCubeUnderSky = R"(
        LookAt 0.3 0.4 5  0 0 0  0 1 0
        Camera "perspective" "float fov" [ 5 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 5 ]
        WorldBegin
        LightSource "infinite" "rgb L" [ 0.8 0.9 1.0 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.3 0.7 ]
        Shape "loopsubdiv" "integer levels" [ 4 ]
            "point3 P" [ -1 -1 -1  1 -1 -1  -1 1 -1  1 1 -1  -1 -1 1  1 -1 1  -1 1 1  1 1 1 ]
            "integer indices" [ 0 2 3  0 3 1  4 5 7  4 7 6  0 1 5  0 5 4  2 6 7  2 7 3  0 4 6  0 6 2  1 3 7  1 7 5 ]
    )";

// A small diffuse disk on the axis of a cylinder of radius R that emits L inwards
// (ReverseOrientation), at the height of its middle; the wall reaches h above it (here R = h
// = 1, made of a cylinder of radius 1 and height 1 scaled by 2 along z). Only the wall above
// lights the disk's upper face: E = 2 pi L int_{atan(R/h)}^{pi/2} cos sin = pi L h^2 / (R^2 +
// h^2), so a camera looking down at the disk sees rho L h^2 / (R^2 + h^2) = rho L / 2.
const char* kDiskInsideCylinder = R"(
        LookAt 0 0 0.5  0 0 0  0 1 0
        Camera "perspective" "float fov" [ 0.5 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 2 3 4 ]
          ReverseOrientation
          Scale 1 1 2
          Shape "cylinder" "float radius" [ 1 ] "float zmin" [ -0.5 ] "float zmax" [ 0.5 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "disk" "float radius" [ 0.05 ]
    )";

// The same cylinder (black, so it emits but does not reflect) seen from its axis: every
// pixel sees the wall's radiance.
const char* kInsideCylinder = R"(
        LookAt 0 0 0  1 0 0.1  0 0 1
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
        PixelFilter "box"
        WorldBegin
        AttributeBegin
          Material "diffuse" "rgb reflectance" [ 0 0 0 ]
          AreaLightSource "diffuse" "rgb L" [ 1 2 3 ]
          ReverseOrientation
          Scale 1 1 2
          Shape "cylinder" "float radius" [ 1 ] "float zmin" [ -0.5 ] "float zmax" [ 0.5 ]
        AttributeEnd
    )";

}  // namespace

// A convex diffuse object under a uniform sky reflects a * L exactly (it never sees itself),
// per channel in RGB mode and per wavelength in spectral mode.
static std::array<double, 3> skyTimesAlbedo(bool spectral) {
    return exactPixel(spectral, product, reflectance({0.5f, 0.3f, 0.7f}), emission({0.8f, 0.9f, 1.0f}));
}

TEST(ExactScenes, DiffuseSphereUnderUniformSky) {
    RenderResult r = renderString(kSphereUnderSky, 64);
    expectWithin4Sigma(wholeImage(r.image), skyTimesAlbedo(defaultSpectral()).data());
}

// The same for the limit surface of a subdivided cube, shaded with its limit normals.
TEST(ExactScenes, SubdividedCubeUnderUniformSky) {
    RenderResult r = renderString(kSubdividedCubeUnderSky, 64);
    expectWithin4Sigma(wholeImage(r.image), skyTimesAlbedo(defaultSpectral()).data());
}

// Direct lighting from a cylinder: light sampling by area (its pdf is 1/area under the
// Scale) and BSDF sampling, combined by MIS, give the closed-form irradiance.
TEST(ExactScenes, DiskLitByTheInsideOfACylinder) {
    RenderResult r = renderString(kDiskInsideCylinder, 256);
    expectWithin4Sigma(wholeImage(r.image), greyLitBy234(0.5).data());
}

// Light tracing starts its paths on the cylinder (sampleArea with density 1/area) and must
// reproduce the wall's radiance that camera rays see directly.
TEST(ExactScenes, CylinderEmitterSeenByLightTracing) {
    // Spectral mode: path tracing's samples as in BidirectionalDirectlySeenLight.
    const bool spectral = defaultSpectral();
    const auto exact = exactPixel(spectral, itself, emission({1, 2, 3}));
    expectExact(wholeImage(renderString(kInsideCylinder, spectral ? 1024 : 4, 7, 0, "path").image), exact, spectral);
    expectWithin4Sigma(wholeImage(renderString(kInsideCylinder, 16384, 7, 0, "light").image), exact.data());
}

// Inside a closed sphere emitting Le with albedo r: pixel = Le * sum_{k=0..d} r^k.
// Every integrator (path, light and bidirectional) must reproduce it, in both colour modes
// (spectrally the same sum per wavelength, through the sensor).
class ClosedFurnace : public ::testing::TestWithParam<std::tuple<const char*, int, bool>> {};

TEST_P(ClosedFurnace, EmittingSphereSeenFromInside) {
    const char* integrator = std::get<0>(GetParam());
    int maxDepth = std::get<1>(GetParam());
    const bool spectral = std::get<2>(GetParam());
    const std::string scene = closedFurnaceScene(maxDepth, "0.5 0.25 1.0", "0.6 0.6 0.6");
    // Light tracing finds the camera only through the lens connection: 8x the samples.
    const int spp = std::string(integrator) == "light" ? (spectral ? 3072 : 2048) : 256;
    RenderResult r = renderString(scene, spp, 7, 0, integrator, spectral);
    const auto exact = exactPixel(
        spectral,
        [maxDepth](double albedo, double Le) {
            double sum = 0;
            for (int k = 0; k <= maxDepth; ++k) sum += std::pow(albedo, k);
            return Le * sum;
        },
        reflectance({0.6f, 0.6f, 0.6f}), emission({0.5f, 0.25f, 1.0f}));
    expectWithin4Sigma(wholeImage(r.image), exact.data());
}

std::string furnaceName(const ::testing::TestParamInfo<ClosedFurnace::ParamType>& i) {
    return std::string(std::get<0>(i.param)) + "_" + std::to_string(std::get<1>(i.param));
}
INSTANTIATE_TEST_SUITE_P(Depths, ClosedFurnace,
                         ::testing::Combine(::testing::Values("path", "light", "bdpt"), ::testing::Values(0, 1, 2, 5, 20),
                                            ::testing::Values(false)),
                         furnaceName);
INSTANTIATE_TEST_SUITE_P(SpectralDepths, ClosedFurnace,
                         ::testing::Combine(::testing::Values("path", "light", "bdpt"), ::testing::Values(0, 2, 20),
                                            ::testing::Values(true)),
                         furnaceName);

// The other exact scenes with light tracing and BDPT, where light tracing can reach the
// camera's view (not the tiny footprints below, which only the camera can find).
TEST(ExactScenes, BidirectionalDiffuseSphereUnderUniformSky) {
    const auto exact = skyTimesAlbedo(defaultSpectral());
    for (const char* integrator : {"light", "bdpt"}) {
        SCOPED_TRACE(integrator);
        // Spectral mode's blue is noisier: light tracing takes a third more samples.
        int spp = std::string(integrator) == "light" ? (defaultSpectral() ? 8192 : 6144) : 64;
        expectWithin4Sigma(wholeImage(renderString(kSphereUnderSky, spp, 7, 0, integrator).image), exact.data());
    }
}

TEST(ExactScenes, BidirectionalDirectlySeenLight) {
    const char* scene = R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
        PixelFilter "box"
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 2 3 ]
          ReverseOrientation
          Shape "disk" "float height" [ 3 ] "float radius" [ 10 ]
        AttributeEnd
    )";
    // BDPT sees it by the camera ray alone (s + t = 2 has one strategy): exact. Light tracing
    // splats points of the disk through the lens: unbiased, with noise. Spectral mode: enough
    // samples that sigma (0.01%) tells its answer from the RGB one (9e-4 apart in red), and
    // half as many again for light tracing's blue.
    const bool spectral = defaultSpectral();
    const auto exact = exactPixel(spectral, itself, emission({1, 2, 3}));
    expectExact(wholeImage(renderString(scene, spectral ? 1024 : 4, 7, 0, "bdpt").image), exact, spectral);
    expectWithin4Sigma(wholeImage(renderString(scene, spectral ? 61440 : 40960, 7, 0, "light").image), exact.data());
}

TEST(ExactScenes, BidirectionalPlaneUnderLights) {
    const double f = 4 * cornerFormFactor(1.0, 0.5, 1.0);
    expectWithin4Sigma(wholeImage(renderString(kPlaneUnderRectangle, 256, 7, 0, "bdpt").image), greyLitBy234(f).data());
    expectWithin4Sigma(wholeImage(renderString(kPlaneUnderPoint, 64, 7, 0, "bdpt").image),
                       greyLitBy234(1 / (M_PI * 4)).data());
}


TEST(ExactScenes, DiffusePlaneUnderRectangularLight) {
    // The camera sits between plane and light (it does not occlude) and sees a tiny spot.
    RenderResult r = renderString(kPlaneUnderRectangle, 256);
    expectWithin4Sigma(wholeImage(r.image), greyLitBy234(4 * cornerFormFactor(1.0, 0.5, 1.0)).data());
}

// A point light of intensity I at height h over a diffuse plane: L = rho I / (pi h^2).
TEST(ExactScenes, DiffusePlaneUnderPointLight) {
    const bool spectral = defaultSpectral();
    RenderResult r = renderString(kPlaneUnderPoint, spectral ? 256 : 16);
    const auto exact = greyLitBy234(1 / (M_PI * 4), spectral);
    // Deterministic in RGB mode up to the footprint's cos^4 falloff (< 1e-5 relative here).
    expectExact(wholeImage(r.image), exact, spectral, 1e-4);
}

// A small sphere light of radius r at height h over a diffuse plane: below its centre the
// sphere subtends a cone of sin^2 = r^2 / h^2, so E = pi L r^2 / h^2 and the plane shows
// rho L r^2 / h^2. Here r = 0.02 at h = 20. The point the cone's direction hits on such a
// sphere was once computed from the difference of two squared distances near h^2, which lost
// the discriminant near the silhouette; the point fell inside the sphere, the shadow ray to it
// was blocked, and the plane came out darker (Veach's MIS scene's smallest light, r = 0.05 at
// about 10, lit the wall 1.3% too dark).
TEST(ExactScenes, DiffusePlaneUnderASmallDistantSphere) {
    const char* scene = R"(
        LookAt 0 0.5 0   0 0 0   0 0 1
        Camera "perspective" "float fov" [ 0.5 ]
        Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 500000 750000 1000000 ]
          Material "diffuse" "rgb reflectance" [ 0 0 0 ]
          Translate 0 20 0
          Shape "sphere" "float radius" [ 0.02 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "trianglemesh" "point3 P" [ -20 0 -20  20 0 -20  20 0 20  -20 0 20 ]
            "integer indices" [ 0 1 2 0 2 3 ]
    )";
    const bool spectral = defaultSpectral();
    const auto exact = greyLitBy(0.02 * 0.02 / (20.0 * 20.0), {500000, 750000, 1000000}, spectral);
    for (const char* integrator : {"path", "bdpt"}) {
        SCOPED_TRACE(integrator);
        expectWithin4Sigma(wholeImage(renderString(scene, spectral ? 256 : 64, 7, 0, integrator).image), exact.data());
    }
}

// "rgb L [1 1 1]" on a light seen directly gives pixel value 1 (as in pbrt-v4).
TEST(ExactScenes, DirectlySeenLightHasItsRadiance) {
    const char* scene = R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          ReverseOrientation
          Shape "disk" "float height" [ 3 ] "float radius" [ 10 ]
        AttributeEnd
    )";
    const bool spectral = defaultSpectral();
    RenderResult r = renderString(scene, spectral ? 64 : 4);
    expectExact(wholeImage(r.image), exactPixel(spectral, itself, emission({1, 1, 1})), spectral);
}

// Every sampler gives an unbiased image: the closed furnace (maxdepth 3) with each.
TEST(ExactScenes, ClosedFurnaceWithEverySampler) {
    const std::string scene = closedFurnaceScene(3, "1 1 1", "0.5 0.5 0.5");
    const double exact[3] = {1.875, 1.875, 1.875};  // 1 + 1/2 + 1/4 + 1/8
    for (const std::string& sampler : samplerNames()) {
        SceneDescription desc = parseSceneString(scene);
        auto s = buildScene(desc);
        auto integrator = createIntegrator("path", *s);
        RenderOptions o;
        o.spp = 64;
        o.seed = 11;
        o.sampler = sampler;
        o.progress = false;
        RenderResult r = render(*s, *integrator, o);
        SCOPED_TRACE(sampler);
        expectWithin4Sigma(wholeImage(r.image), exact);
    }
}
