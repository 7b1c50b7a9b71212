// Light types against closed forms, and light sampling densities against pdfLi.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "image/image.h"
#include "lights/infinite_lights.h"
#include "math/warp.h"
#include "mc/rng.h"
#include "render_helpers.h"
#include "spectral_answer.h"

using namespace ps;
using namespace ps::test;
namespace fs = std::filesystem;

namespace {

// A camera between a big diffuse plane (y = 0, albedo 0.5) and whatever lights it, looking
// straight down at a tiny spot around the origin.
std::string planeScene(const std::string& lights, int maxDepth = 1) {
    return R"(
        LookAt 0 0.5 0   0 0 0   0 0 1
        Camera "perspective" "float fov" [ 0.5 ]
        Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ )" + std::to_string(maxDepth) + R"( ]
        WorldBegin
    )" + lights + R"(
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "trianglemesh" "point3 P" [ -50 0 -50  50 0 -50  50 0 50  -50 0 50 ]
            "integer indices" [ 0 1 2 0 2 3 ]
    )";
}

double centreValue(const std::string& scene, int spp = 16) {
    RenderResult r = renderString(scene, spp);
    return wholeImage(r.image).mean[1];
}

}  // namespace

// Distant light of radiance L from 60 degrees off the normal: E = L cos(60), Lo = rho E / pi
// (deterministic in RGB mode; spectral mode evaluates it per wavelength, with noise).
TEST(Lights, DistantLight) {
    const bool spectral = defaultSpectral();
    const std::string scene =
        planeScene(R"(LightSource "distant" "rgb L" [ 3 3 3 ] "point3 from" [ 0 1 1.7320508 ] "point3 to" [ 0 0 0 ])");
    const RegionStats s = wholeImage(renderString(scene, spectral ? 256 : 16).image);
    const auto exact = exactPixel(
        spectral, [](double rho, double L) { return rho * L * 0.5 / M_PI; }, reflectance({0.5f, 0.5f, 0.5f}),
        emission({3, 3, 3}));
    expectExact(s, exact, spectral, 1e-4);
}

// A spot light straight above: inside its cone it is a point light; outside, dark.
TEST(Lights, SpotLight) {
    double inside = centreValue(planeScene(R"(LightSource "spot" "rgb I" [ 2 2 2 ] "point3 from" [ 0 2 0 ] "point3 to" [ 0 0 0 ] "float coneangle" [ 20 ])"));
    EXPECT_NEAR(inside, 0.5 * 2 / (M_PI * 4), 1e-4);
    double outside = centreValue(planeScene(R"(LightSource "spot" "rgb I" [ 2 2 2 ] "point3 from" [ 0 2 0 ] "point3 to" [ 5 0 0 ] "float coneangle" [ 20 ])"));
    EXPECT_EQ(outside, 0.0);
}

// "power" on a point light: I = P / (4 pi), multiplied by the RGB value (PBRT-CONVENTIONS §3).
TEST(Lights, PointLightPower) {
    double v = centreValue(planeScene(R"(LightSource "point" "rgb I" [ 2 2 2 ] "float power" [ 100 ] "point3 from" [ 0 2 0 ])"));
    EXPECT_NEAR(v, 0.5 * 2 * (100 / (4 * M_PI)) / (M_PI * 4), 1e-3);
}

// A spherical emitter (sampled by its cone of directions) above the plane, radius r at height
// h: the irradiance of a uniform sphere is pi L (r/h)^2 on the axis, so Lo = rho L (r/h)^2.
TEST(Lights, SphereLightIrradiance) {
    RenderResult r = renderString(planeScene(R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]
          Translate 0 3 0
          Shape "sphere" "float radius" [ 0.6 ]
        AttributeEnd)"), 256);
    RegionStats s = wholeImage(r.image);
    double exact = 0.5 * 4 * (0.6 / 3) * (0.6 / 3);
    EXPECT_NEAR(s.mean[1], exact, 4 * s.stdErr[1] + 1e-4 * exact);
    EXPECT_LT(s.stdErr[1], 0.02 * exact);
}

// A disk light parallel to the plane, radius R at height h: E = pi L R^2 / (R^2 + h^2).
TEST(Lights, DiskLightIrradiance) {
    RenderResult r = renderString(planeScene(R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 2 2 2 ]
          Translate 0 1.5 0
          Rotate 90 1 0 0
          Shape "disk" "float radius" [ 1 ]
        AttributeEnd)"), 256);
    RegionStats s = wholeImage(r.image);
    double exact = 0.5 * 2 * 1.0 / (1.0 + 1.5 * 1.5);
    EXPECT_NEAR(s.mean[1], exact, 4 * s.stdErr[1] + 1e-4 * exact);
    EXPECT_LT(s.stdErr[1], 0.02 * exact);
}

// An instanced sphere under a uniform sky still reflects albedo * L.
TEST(Lights, InstancedObjectUnderUniformSky) {
    RenderResult r = renderString(R"(
        LookAt 0 0 5  0 0 0  0 1 0
        Camera "perspective" "float fov" [ 8 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        WorldBegin
        LightSource "infinite" "rgb L" [ 1 1 1 ]
        ObjectBegin "ball"
          Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
          Scale 0.5 0.5 0.5
          Shape "sphere" "float radius" [ 2 ]
        ObjectEnd
        Translate 0 0 0.5
        ObjectInstance "ball"
    )", 64);
    RegionStats s = wholeImage(r.image);
    EXPECT_NEAR(s.mean[1], 0.6, 4 * s.stdErr[1] + 1e-4);
}

// Environment maps: sampleLi's density equals pdfLi, and a constant map behaves like the
// uniform sky (pixel = albedo * L) in both layouts.
TEST(Lights, ImageEnvironmentSamplingAndConstantMap) {
    fs::path dir = fs::temp_directory_path() / ("pathspace-env-" + std::to_string(getpid()));
    fs::create_directories(dir);
    for (auto [w, h, name] : {std::tuple{32, 32, "sq.pfm"}, std::tuple{64, 32, "ll.pfm"}}) {
        Image img(w, h);
        Rng rng(3);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) img.set(x, y, Spectrum(0.1f + 4 * rng.uniform()));
        writeImage((dir / name).string(), img);
        ImageInfiniteLight light(img, 1.0f, Transform::rotate(30, {1, 2, 3}),
                                 w == h ? ImageInfiniteLight::Layout::EqualArea : ImageInfiniteLight::Layout::LatLong);
        light.preprocess({0, 0, 0}, 1);
        // sampleLi's density agrees with pdfLi (directions landing on a texel boundary may be
        // looked up in the neighbour after rounding: allow a few of those).
        const int n = 20000;
        int mismatches = 0;
        double sum = 0, sum2 = 0;
        for (int i = 0; i < n; ++i) {
            auto ls = light.sampleLi({{0, 0, 0}, {0, 0, 1}}, {rng.uniform(), rng.uniform()});
            ASSERT_TRUE(ls.has_value());
            float p = light.pdfLi({{0, 0, 0}, {0, 0, 1}}, ls->wi, nullptr);
            if (std::fabs(p - ls->pdf) > 2e-3f * ls->pdf) ++mismatches;
            double v = ls->L.g / ls->pdf;
            sum += v;
            sum2 += v * v;
        }
        EXPECT_LT(mismatches, n / 200) << name;
        // E[L/pdf] = integral of L over the sphere: texel values times their solid angles.
        double exact = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double omega = w == h ? 4 * M_PI / (w * h)
                                      : (2 * M_PI / w) * (std::cos(M_PI * y / h) - std::cos(M_PI * (y + 1) / h));
                exact += img.get(x, y).g * omega;
            }
        double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, exact, 4 * se + 1e-4 * exact) << name;
        Image flat(w, h);
        for (float& v : flat.rgb) v = 0.8f;
        writeImage((dir / ("flat-" + std::string(name))).string(), flat);
        RenderResult r = renderString(R"(
            LookAt 0 0 5  0 0 0  0 1 0
            Camera "perspective" "float fov" [ 10 ]
            Film "rgb" "integer xresolution" [ 12 ] "integer yresolution" [ 12 ]
            PixelFilter "box"
            WorldBegin
            LightSource "infinite" "string filename" [ ")" + (dir / ("flat-" + std::string(name))).string() + R"(" ]
            Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
            Shape "sphere" "float radius" [ 1 ]
        )", 64);
        RegionStats s = wholeImage(r.image);
        EXPECT_NEAR(s.mean[1], 0.4, 4 * s.stdErr[1] + 1e-4) << name;
    }
    fs::remove_all(dir);
}
