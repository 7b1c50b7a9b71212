// Bump and normal maps in renders: a diffuse plane whose map tilts its shading normal by a
// known angle, under a distant light, has radiance rho/pi L cos(angle between the light and
// the tilted normal), for the path tracer and for light tracing and BDPT, whose light
// subpaths need the adjoint BSDF's shading-normal factor (thesis §5.3) at the mapped frame.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "image/image.h"
#include "render/scene.h"
#include "render_helpers.h"
#include "transport/integrator.h"

using namespace ps;
using namespace ps::test;
namespace fs = std::filesystem;

namespace {

constexpr double kRho = 0.5, kL = 3;
const double kAlpha = M_PI / 3;  // the light, 60 degrees from the plane's normal towards +x
const double kBeta = M_PI / 6;   // each map tilts the normal 30 degrees towards +x

class ShadingDetailRender : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("pathspace-shading-detail-" + std::to_string(getpid()));
        fs::create_directories(dir_);
        // Float images (read linearly): the tilted normal (sin b, 0, cos b) as (n + 1) / 2 in
        // the tangent frame x = dp/du = +x, z = +y; the flat normal (0, 0, 1).
        Image tilted(1, 1), flat(1, 1), ramp(2, 1);
        tilted.set(0, 0, Spectrum(float((std::sin(kBeta) + 1) / 2), 0.5f, float((std::cos(kBeta) + 1) / 2)));
        flat.set(0, 0, Spectrum(0.5f, 0.5f, 1));
        // Texel centres at s = 0.25 (value 1) and 0.75 (value 0): linear between them, with
        // slope -2 per unit u.
        ramp.set(0, 0, Spectrum(1));
        ramp.set(1, 0, Spectrum(0));
        writeImage((dir_ / "tilted.pfm").string(), tilted);
        writeImage((dir_ / "flat.pfm").string(), flat);
        writeImage((dir_ / "ramp.pfm").string(), ramp);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // A 1.2 x 1.2 plane at y = 0 (normal +y) with u = (x + 0.6) / 1.2, v = (z + 0.6) / 1.2,
    // so dp/du = (1.2, 0, 0); the camera above sees u in [0.28, 0.72].
    std::string scene(const std::string& material, int maxDepth = 1, const std::string& textures = "") const {
        return R"(
            LookAt 0 1 0   0 0 0   0 0 1
            Camera "perspective" "float fov" [ 30 ]
            Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
            PixelFilter "box"
            Integrator "path" "integer maxdepth" [ )" + std::to_string(maxDepth) + R"( ]
            WorldBegin
            LightSource "distant" "rgb L" [ 3 3 3 ] "point3 from" [ )" + std::to_string(std::sin(kAlpha)) + " " +
               std::to_string(std::cos(kAlpha)) + R"( 0 ] "point3 to" [ 0 0 0 ]
            )" + textures + R"(
            Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ] )" + material + R"(
            Shape "trianglemesh" "point3 P" [ -0.6 0 -0.6  -0.6 0 0.6  0.6 0 0.6  0.6 0 -0.6 ]
                "point2 uv" [ 0 0  0 1  1 1  1 0 ]
                "integer indices" [ 0 1 2 0 2 3 ]
        )";
    }
    std::string path(const char* file) const { return (dir_ / file).string(); }
    // A displacement d(u) = scale (1 - 2 (u - 0.25)): dd/du = -2 scale; with scale =
    // 1.2 tan(b) / 2 the bump tilts the normal by b towards +x (tan b = -(dd/du) / |dp/du|).
    std::string rampTextures() const {
        return R"(Texture "ramp" "float" "imagemap" "string filename" [ ")" + path("ramp.pfm") +
               R"(" ] "string wrap" [ "clamp" ]
                  Texture "bump" "float" "scale" "texture tex" [ "ramp" ] "float scale" [ )" +
               std::to_string(1.2 * std::tan(kBeta) / 2) + " ]\n";
    }
    fs::path dir_;
};

// The path tracer's direct lighting of the plane is exact in RGB mode; spectral mode adds the
// wavelengths' noise, and 0.5% still tells every wrong answer below apart.
const int kPathSpp = defaultSpectral() ? 16 : 4;
const double kPathRelStdErr = defaultSpectral() ? 0.005 : 1e-4;

// Every pixel's expectation is rho/pi L cos(alpha - beta); the pixels' spread gives sigma.
void expectTiltedRadiance(const RegionStats& s, const char* what, double maxRelStdErr) {
    const double exact = kRho / M_PI * kL * std::cos(kAlpha - kBeta);
    double sigma = s.stdErr[1];
    std::printf("  %s: %.6f +- %.6f (%.3f%%), exact %.6f, %+.2f sigma\n", what, s.mean[1], sigma, 100 * sigma / exact, exact,
                (s.mean[1] - exact) / std::max(sigma, 1e-12));
    EXPECT_NEAR(s.mean[1], exact, 4 * sigma + 1e-5 * exact) << what;
    EXPECT_LT(sigma, maxRelStdErr * exact) << what << ": too noisy to tell";
}

// The tilt is 30 degrees, the light 60: the unmapped plane would give cos 60 = 0.5 of the
// normal-incidence value instead of cos 30 = 0.866, and light tracing without the adjoint
// factor at the mapped normal cos 60 cos 30 = 0.433.
TEST_F(ShadingDetailRender, ConstantNormalMapGivesTheTiltedCosine) {
    std::string s = scene(R"("string normalmap" [ ")" + path("tilted.pfm") + R"(" ])");
    expectTiltedRadiance(wholeImage(renderString(s, kPathSpp, 7, 0, "path").image), "path", kPathRelStdErr);
    expectTiltedRadiance(wholeImage(renderString(s, 16384, 7, 0, "light").image), "light", 0.005);
    expectTiltedRadiance(wholeImage(renderString(s, 16, 7, 0, "bdpt").image), "bdpt", 0.005);
}

TEST_F(ShadingDetailRender, LinearBumpGivesTheTiltedCosine) {
    std::string s = scene(R"("texture displacement" [ "bump" ])", 1, rampTextures());
    expectTiltedRadiance(wholeImage(renderString(s, kPathSpp, 7, 0, "path").image), "path", kPathRelStdErr);
    expectTiltedRadiance(wholeImage(renderString(s, 16384, 7, 0, "light").image), "light", 0.005);
    expectTiltedRadiance(wholeImage(renderString(s, 16, 7, 0, "bdpt").image), "bdpt", 0.005);
}

// The shading normal at a hit, through the scene's own intersection and surfaceBxDF.
TEST_F(ShadingDetailRender, LinearBumpTiltsTheHitsShadingNormal) {
    setWarningsQuiet(true);
    auto built = buildScene(parseSceneString(scene(R"("texture displacement" [ "bump" ])", 1, rampTextures()), ".", "<test>"));
    for (float x : {-0.2f, 0.0f, 0.25f}) {
        SurfaceInteraction si;
        ASSERT_TRUE(built->intersect(Ray{Vec3(x, 1, 0.1f), Vec3(0, -1, 0), 1e30f}, si));
        ScratchBuffer scratch;
        ASSERT_TRUE(surfaceBxDF(si, scratch));
        std::printf("  x = %.2f: ns (%.6f %.6f %.6f), expected (%.6f %.6f 0)\n", x, si.ns.x, si.ns.y, si.ns.z,
                    std::sin(kBeta), std::cos(kBeta));
        EXPECT_NEAR(si.ns.x, std::sin(kBeta), 2e-4);
        EXPECT_NEAR(si.ns.y, std::cos(kBeta), 2e-4);
        EXPECT_NEAR(si.ns.z, 0, 2e-4);
        EXPECT_EQ(si.ng.y, 1.0f);  // the geometric normal stays
    }
}

// A flat map, (0.5, 0.5, 1), changes nothing: the same seeds give the same image up to the
// rounding of the rebuilt frame, here with interreflection between the plane and a sphere.
TEST_F(ShadingDetailRender, FlatNormalMapLeavesTheImage) {
    const std::string sphere = R"(
        AttributeBegin
          Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]
          Translate 0.1 0.15 0.05
          Shape "sphere" "float radius" [ 0.15 ]
        AttributeEnd
    )";
    std::string plain = scene("", 5, sphere);
    std::string mapped = scene(R"("string normalmap" [ ")" + path("flat.pfm") + R"(" ])", 5, sphere);
    for (const char* integrator : {"path", "bdpt"}) {
        Image a = renderString(plain, 16, 7, 0, integrator).image;
        Image b = renderString(mapped, 16, 7, 0, integrator).image;
        double s = 0, s2 = 0, worst = 0, mean = wholeImage(a).mean[1];
        const int n = a.width * a.height;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                double d = double(b.get(x, y).g) - a.get(x, y).g;
                s += d;
                s2 += d * d;
                worst = std::max(worst, std::fabs(d));
            }
        double diff = s / n, sigma = std::sqrt(std::max(0.0, s2 / n - diff * diff) / n);
        std::printf("  %s: image mean %.6f, mean difference %.3g +- %.3g, largest pixel difference %.3g\n", integrator,
                    mean, diff, sigma, worst);
        EXPECT_LE(std::fabs(diff), 4 * sigma + 1e-6 * mean) << integrator;
        EXPECT_LT(worst, 1e-3 * mean) << integrator << ": a pixel changed";
    }
}

}  // namespace
