// Lights defined by images (pbrt-v4's semantics): goniometric and projection point lights
// and diffuse area lights with an emission image, against hand-computed values.
// The renders here are deterministic in RGB mode (lights seen directly, or one bounce of a delta
// light seen through a tiny field of view), so values are exact up to float rounding; spectral
// mode evaluates the same answers per wavelength, with the wavelengths' noise.
#include <gtest/gtest.h>

#include <cstdio>

#include "lights/light.h"
#include "math/warp.h"
#include "mc/rng.h"
#include "render_helpers.h"
#include "spectral_answer.h"
#include "temp_images.h"

using namespace ps;
using namespace ps::test;

namespace {

// A world holding the given lights (and a small sphere far away, so the scene has bounds).
std::unique_ptr<Scene> worldScene(const std::string& world) {
    setWarningsQuiet(true);
    return buildScene(parseSceneString(R"(
        LookAt 0 0 5  0 0 0  0 1 0
        Camera "perspective"
        Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
        WorldBegin
        AttributeBegin
          Translate 50 50 50
          Shape "sphere" "float radius" [ 0.1 ]
        AttributeEnd
    )" + world, ".", "<test>"));
}

const Light& lastLight(const Scene& s) { return *s.lights().back(); }

// Irradiance at p (normal n) from a delta light, by its sampleLi.
Spectrum irradiance(const Light& l, Vec3 p, Vec3 n) {
    auto ls = l.sampleLi({p, n}, {0.5f, 0.5f});
    if (!ls) return {};
    return ls->L * std::fabs(dot(n, ls->wi));
}

void expectSpectrumNear(Spectrum a, Spectrum b, double rel, const std::string& what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], rel * std::max(1e-6f, std::fabs(b[c]))) << what << " channel " << c;
}

// A camera at `eye` looking at `at` through a tiny field of view, a box-filtered 4 x 4 film,
// one bounce of path tracing: the image mean is the radiance leaving the spot at `at`.
std::string spotView(Vec3 eye, Vec3 at, Vec3 up) {
    char buf[512];
    std::snprintf(buf, sizeof buf, R"(
        LookAt %g %g %g  %g %g %g  %g %g %g
        Camera "perspective" "float fov" [ 0.5 ]
        Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
    )", eye.x, eye.y, eye.z, at.x, at.y, at.z, up.x, up.y, up.z);
    return buf;
}

// A white diffuse plane y = 0 of albedo 0.5.
const char* kGroundPlane = R"(
    Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
    Shape "trianglemesh" "point3 P" [ -50 0 -50  50 0 -50  50 0 50  -50 0 50 ] "integer indices" [ 0 1 2 0 2 3 ]
)";

Spectrum imageMean(const std::string& scene) {
    RenderResult r = renderString(scene, 4);
    RegionStats s = wholeImage(r.image);
    return {float(s.mean[0]), float(s.mean[1]), float(s.mean[2])};
}

// A render's image mean against `exact`: to `rel` of it in RGB mode; in spectral mode within 4
// sigma of the wavelengths' noise (expectSpectralMean), with samples enough (sigma 0.02%) to
// tell the spectral answer from the RGB one.
void expectRendered(const std::string& scene, const std::array<double, 3>& exact, double rel, const std::string& what) {
    const bool spectral = defaultSpectral();
    const RegionStats s = wholeImage(renderString(scene, spectral ? 1024 : 4).image);
    if (spectral) return expectSpectralMean(s, exact, what);
    expectSpectrumNear(Spectrum(float(s.mean[0]), float(s.mean[1]), float(s.mean[2])),
                       Spectrum(float(exact[0]), float(exact[1]), float(exact[2])), rel, what);
}

const Lifted kGrey = reflectance({0.5f, 0.5f, 0.5f});

}  // namespace

// A goniometric light whose image is constant c is a point light of intensity c I (with any
// transform), and with "power" P it is the point light of power P.
TEST(ImageLights, GoniometricConstantImageIsPointLight) {
    TempImages tmp("gonio-const");
    Image img(8, 8);
    for (float& v : img.rgb) v = 0.7f;
    std::string file = tmp.write("const.pfm", img);
    for (bool power : {false, true}) {
        std::string extra = power ? R"( "float power" [ 20 ])" : "";
        auto gonio = worldScene(R"(
            Translate 0.3 1 -0.2
            Rotate 40 1 1 0
            LightSource "goniometric" "rgb I" [ 1 2 3 ] "float scale" [ 2 ] "string filename" [ ")" + file + "\" ]" + extra);
        auto point = worldScene(R"(
            Translate 0.3 1 -0.2
            LightSource "point" "rgb I" [ 1 2 3 ] "float scale" [ )" + std::string(power ? "2" : "1.4") + " ]" + extra);
        const Light& g = lastLight(*gonio);
        const Light& p = lastLight(*point);
        Rng rng(3);
        for (int i = 0; i < 200; ++i) {
            Vec3 at(4 * rng.uniform() - 2, 4 * rng.uniform() - 2, 4 * rng.uniform() - 2);
            Vec3 n = sampleUniformSphere({rng.uniform(), rng.uniform()});
            expectSpectrumNear(irradiance(g, at, n), irradiance(p, at, n), 1e-5, power ? "power" : "scale");
        }
        expectSpectrumNear(g.phi(), p.phi(), 1e-5, "phi");
    }
    // Rendered: a plane lit from 2 above by I = 0.7 * (1, 2, 3): radiance rho / pi * I / 4.
    const std::string scene = spotView({0, 0.5f, 0}, {0, 0, 0}, {0, 0, 1}) + R"(
        AttributeBegin
          Translate 0 2 0
          LightSource "goniometric" "rgb I" [ 1 2 3 ] "string filename" [ ")" + file + R"(" ]
        AttributeEnd
    )" + kGroundPlane;
    const auto exact = exactPixel(
        defaultSpectral(), [](double rho, double I) { return rho / M_PI * 0.7 * I / 4; }, kGrey, emission({1, 2, 3}));
    expectRendered(scene, exact, 1e-4, "render");
}

// One hot texel: (x, y) = (5, 2) of an 8 x 8 map, centre (u, v) = (0.6875, 0.3125). Worked by
// hand through the equal-area mapping: (2u - 1, 2v - 1) = (0.375, -0.375), so r = 0.75,
// phi = pi / 4, z = 1 - r^2 = 0.4375, |xy| = r sqrt(2 - r^2) = 0.899218, i.e. the image-space
// direction (0.635844, -0.635844, 0.4375). The LightSource frame swaps y and z (pbrt-v4), so
// with the identity transform the lit direction is (0.635844, 0.4375, -0.635844); mirrored
// directions, the unswapped one, and the lower hemisphere are dark.
TEST(ImageLights, GoniometricFrameConvention) {
    TempImages tmp("gonio-frame");
    Image img(8, 8);
    img.set(5, 2, Spectrum(3, 3, 3));
    std::string file = tmp.write("hot.pfm", img);
    const float a = 0.635844f, b = 0.4375f;
    struct Case {
        const char* transform;
        Vec3 dir;
        bool lit;
    };
    const Case cases[] = {
        {"", {a, b, -a}, true},
        {"", {-a, b, -a}, false},  // x mirrored
        {"", {a, b, a}, false},    // image rows flipped
        {"", {a, -a, b}, false},   // no y-z swap
        {"", {a, -b, -a}, false},  // the other hemisphere of the image
        // The transform acts after the swap: Rotate 90 about z takes (x, y, z) to (-y, x, z).
        {"Rotate 90 0 0 1", {-b, a, -a}, true},
        {"Rotate 90 0 0 1", {a, b, a}, false},  // the swap applied after the rotation
    };
    for (const Case& c : cases) {
        auto scene = worldScene(std::string(c.transform) + R"(
            LightSource "goniometric" "string filename" [ ")" + file + R"(" ]
        )");
        Vec3 at = normalize(c.dir) * 2;
        Spectrum E = irradiance(lastLight(*scene), at, -normalize(c.dir));
        std::printf("goniometric: transform \"%s\", direction (%.4f %.4f %.4f): E %.6f\n", c.transform, c.dir.x,
                    c.dir.y, c.dir.z, double(E.g));
        if (c.lit) expectSpectrumNear(E, Spectrum(3.0f / 4), 1e-5, c.transform);
        else EXPECT_EQ(E.g, 0.0f) << c.transform << " (" << c.dir.x << " " << c.dir.y << " " << c.dir.z << ")";
    }
}

// A projection light at the origin with the identity transform, fov 60 (tan 30 = t), a
// 4 x 2 image (aspect 2: the screen is [-2, 2] x [-1, 1], each texel one unit square). Texel
// (x, y) centres at screen (sx, sy) = (x - 1.5, y - 0.5) of the light's own frame, whose y is
// the world's -y (pbrt-v4 flips it), so row 0 is the top: texel (x, y) lights the world
// direction (sx t, -sy t, 1). On the plane z = 2 facing the
// light, E = scale * texel * cos / r^2. By hand for texel (3, 0): direction
// (0.866025, 0.288675, 1), |d|^2 = 1.833333, r^2 = 7.333333, cos = 0.738549, so with
// texel red 4 and scale 2, E_red = 8 * 0.738549 / 7.333333 = 0.805690.
TEST(ImageLights, ProjectionPixelsAndFrustum) {
    TempImages tmp("projection");
    Image img(4, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) img.set(x, y, Spectrum(1 + x + 4 * y, 0.5f * (1 + x), 0.25f * (1 + y)));
    std::string file = tmp.write("slide.pfm", img);
    auto scene = worldScene(R"(LightSource "projection" "float fov" [ 60 ] "float scale" [ 2 ] "string filename" [ ")" +
                            file + R"(" ])");
    const Light& l = lastLight(*scene);
    const Vec3 n(0, 0, -1);
    const float t = std::tan(float(M_PI) / 6);
    EXPECT_NEAR(irradiance(l, {1.732051f, 0.577350f, 2}, n).r, 0.805690f, 2e-6f);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) {
            float sx = x - 1.5f, sy = y - 0.5f;
            Vec3 d(sx * t, -sy * t, 1);
            float cosT = 1 / length(d), r2 = 4 * lengthSquared(d);
            Spectrum expected = img.get(x, y) * (2 * cosT / r2);
            expectSpectrumNear(irradiance(l, d * 2, n), expected, 1e-5, "texel " + std::to_string(x) + "," + std::to_string(y));
        }
    // The frustum: x reaches 2 t (aspect 2), y only t; nothing behind the light.
    auto E = [&](Vec3 d) { return irradiance(l, d * 2, n).g; };
    EXPECT_GT(E({1.95f * t, 0.5f * t, 1}), 0.0f);
    EXPECT_EQ(E({2.05f * t, 0.5f * t, 1}), 0.0f);
    EXPECT_GT(E({0.5f * t, 0.95f * t, 1}), 0.0f);
    EXPECT_EQ(E({0.5f * t, 1.05f * t, 1}), 0.0f);
    EXPECT_EQ(E({-0.5f * t, -1.05f * t, 1}), 0.0f);
    EXPECT_EQ(irradiance(l, {0.1f, 0.1f, -2}, {0, 0, 1}).g, 0.0f);

    // A tall image (aspect 1/2): the screen is [-1, 1] x [-2, 2], fov spans x.
    Image tall(2, 4);
    for (float& v : tall.rgb) v = 1;
    std::string tallFile = tmp.write("tall.pfm", tall);
    auto scene2 = worldScene(R"(LightSource "projection" "float fov" [ 60 ] "string filename" [ ")" + tallFile + R"(" ])");
    const Light& l2 = lastLight(*scene2);
    EXPECT_GT(irradiance(l2, Vec3(0.5f * t, 1.95f * t, 1) * 2, n).g, 0.0f);
    EXPECT_EQ(irradiance(l2, Vec3(0.5f * t, 2.05f * t, 1) * 2, n).g, 0.0f);
    EXPECT_EQ(irradiance(l2, Vec3(1.05f * t, 0.5f * t, 1) * 2, n).g, 0.0f);

    // Rendered: aimed straight down from 2 above the plane, a 3 x 3 image's centre texel
    // lights the spot below: radiance rho / pi * texel / 4.
    Image nine(3, 3);
    nine.set(1, 1, Spectrum(0.4f, 0.8f, 1.2f));
    nine.set(0, 1, Spectrum(9, 9, 9));
    std::string nineFile = tmp.write("nine.pfm", nine);
    const std::string lit = spotView({0, 0.5f, 0}, {0, 0, 0}, {0, 0, 1}) + R"(
        AttributeBegin
          Translate 0 2 0
          Rotate 90 1 0 0
          LightSource "projection" "float fov" [ 30 ] "string filename" [ ")" + nineFile + R"(" ]
        AttributeEnd
    )" + kGroundPlane;
    // The texel is lifted as an illuminant, as "rgb I" is.
    const auto exact = exactPixel(
        defaultSpectral(), [](double rho, double texel) { return rho / M_PI * texel / 4; }, kGrey,
        emission({0.4f, 0.8f, 1.2f}));
    expectRendered(lit, exact, 1e-4, "render");
}

// An area light with an image: a square (bilinear patch, uv = ((x + 1) / 2, (y + 1) / 2))
// facing +z emits scale times the image at (u, 1 - v), bilinearly interpolated. The 8 x 8
// image is 4 x 4 blocks of 2 x 2 equal texels, so around a block's centre (a texel corner)
// the interpolation is the block's value; block (bx, by) centres at u = (2 bx + 1) / 8 and
// 1 - v = (2 by + 1) / 8: block (0, 0), the image's top left, is the square's -x, +y corner.
TEST(ImageLights, AreaLightImageSeenByCamera) {
    TempImages tmp("area-image");
    Image img(8, 8);
    auto block = [](int bx, int by) { return Spectrum(1 + bx, 1 + by, 0.5f + 0.25f * (bx + by)); };
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) img.set(x, y, block(x / 2, y / 2));
    std::string file = tmp.write("emit.pfm", img);
    std::string light = R"(
        AreaLightSource "diffuse" "float scale" [ 1.5 ] "string filename" [ ")" + file + R"(" ]
        Shape "bilinearmesh" "point3 P" [ -1 -1 0  1 -1 0  -1 1 0  1 1 0 ]
    )";
    for (auto [bx, by] : {std::pair{0, 0}, {3, 0}, {1, 2}, {2, 3}}) {
        float u = (2 * bx + 1) / 8.0f, v = 1 - (2 * by + 1) / 8.0f;
        Vec3 at(2 * u - 1, 2 * v - 1, 0);
        std::printf("area image: block (%d, %d) at (%.3f, %.3f)\n", bx, by, at.x, at.y);
        // The texels are lifted as illuminants, as "rgb L" is.
        const Spectrum b = block(bx, by);
        const auto exact = exactPixel(defaultSpectral(), [](double L) { return 1.5 * L; }, emission({b.r, b.g, b.b}));
        expectRendered(spotView(at + Vec3(0.3f, 0.2f, 2), at, {0, 1, 0}) + light, exact, 1e-5,
                       "block " + std::to_string(bx) + "," + std::to_string(by));
    }
    // One-sided: the back shows nothing.
    Spectrum back = imageMean(spotView({0.1f, 0.1f, -2}, {0.1f, 0.1f, 0}, {0, 1, 0}) + light);
    EXPECT_EQ(back.g, 0.0f);
}

// "L" and "filename" together are an error (pbrt-v4), located at the AreaLightSource; a
// projection light needs "filename"; non-square goniometric maps are rejected.
TEST(ImageLights, BadParametersAreLocatedErrors) {
    TempImages tmp("light-errors");
    Image img(4, 2);
    for (float& v : img.rgb) v = 1;
    std::string file = tmp.write("wide.pfm", img);
    auto expectError = [](const std::string& world, const std::string& needle) {
        try {
            worldScene(world);
            ADD_FAILURE() << "no error for: " << world;
        } catch (const InputError& e) {
            std::string msg = e.what();
            EXPECT_NE(msg.find("<test>:"), std::string::npos) << msg;
            EXPECT_NE(msg.find(needle), std::string::npos) << msg;
        }
    };
    expectError(R"(AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "string filename" [ ")" + file + R"(" ]
                   Shape "sphere")", "both \"L\" and \"filename\"");
    expectError(R"(LightSource "projection" "float fov" [ 45 ])", "\"filename\" is required");
    expectError(R"(LightSource "goniometric" "string filename" [ ")" + file + R"(" ])", "must be square");
    expectError(R"(LightSource "projection" "string filename" [ "no-such-slide.pfm" ])", "no-such-slide.pfm");
}
