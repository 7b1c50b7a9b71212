// Camera "spherical" with pbrt-v4's semantics: which film point looks where under both
// mappings, the equal-area mapping's uniform coverage of the sphere, and renders through it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "camera/camera.h"
#include "mc/rng.h"
#include "render_helpers.h"
#include "spectral_answer.h"

using namespace ps;
using namespace ps::test;

namespace {

Camera sphericalCamera(SphericalMapping m, int xRes, int yRes, const Transform& worldFromCamera = Transform()) {
    Camera::Params p;
    p.projection = Camera::Projection::Spherical;
    p.mapping = m;
    p.xRes = xRes;
    p.yRes = yRes;
    p.worldFromCamera = worldFromCamera;
    return Camera(p);
}

void expectDir(const Camera& cam, Vec2 pFilm, Vec3 expected) {
    Ray r = cam.generateRay({pFilm, {0.5f, 0.5f}});
    EXPECT_NEAR(r.d.x, expected.x, 1e-5f) << "film (" << pFilm.x << ", " << pFilm.y << ")";
    EXPECT_NEAR(r.d.y, expected.y, 1e-5f) << "film (" << pFilm.x << ", " << pFilm.y << ")";
    EXPECT_NEAR(r.d.z, expected.z, 1e-5f) << "film (" << pFilm.x << ", " << pFilm.y << ")";
}

}  // namespace

// Equal-area (the default): the octahedral square with y and z swapped. Film centre = up,
// corners = down, right-middle = +x, bottom-middle = forward, top-middle = backward.
TEST(SphericalCamera, EqualAreaDirections) {
    Camera cam = sphericalCamera(SphericalMapping::EqualArea, 64, 64);
    expectDir(cam, {32, 32}, {0, 1, 0});
    for (Vec2 corner : {Vec2(0, 0), Vec2(64, 0), Vec2(0, 64), Vec2(64, 64)}) expectDir(cam, corner, {0, -1, 0});
    expectDir(cam, {64, 32}, {1, 0, 0});
    expectDir(cam, {0, 32}, {-1, 0, 0});
    expectDir(cam, {32, 64}, {0, 0, 1});
    expectDir(cam, {32, 0}, {0, 0, -1});
    // (u, v) = (3/4, 3/4) lies on the octahedron's equator, halfway between +x and +z.
    const float h = std::sqrt(0.5f);
    expectDir(cam, {48, 48}, {h, 0, h});
    // (1/2, 3/4): r = 1/2 from the centre, so height 1 - r^2 = 3/4 above the horizon,
    // towards +z, horizontal part r sqrt(2 - r^2).
    expectDir(cam, {32, 48}, {0, 0.75f, 0.5f * std::sqrt(1.75f)});
    // Film points the filter puts beyond an edge fold back, mirrored about that edge's
    // midpoint: (-0.1, 0.3) -> (0.1, 0.7), (1.1, 0.2) -> (0.9, 0.8), (0.3, -0.1) -> (0.7, 0.1),
    // (0.6, 1.2) -> (0.4, 0.8).
    auto dirAt = [&](Vec2 uv) { return cam.generateRay({uv * 64.0f, {0.5f, 0.5f}}).d; };
    expectDir(cam, Vec2(-0.1f, 0.3f) * 64.0f, dirAt({0.1f, 0.7f}));
    expectDir(cam, Vec2(1.1f, 0.2f) * 64.0f, dirAt({0.9f, 0.8f}));
    expectDir(cam, Vec2(0.3f, -0.1f) * 64.0f, dirAt({0.7f, 0.1f}));
    expectDir(cam, Vec2(0.6f, 1.2f) * 64.0f, dirAt({0.4f, 0.8f}));
}

// Equirectangular: theta = pi v from up, phi = 2 pi u from +x towards +z.
TEST(SphericalCamera, EquirectangularDirections) {
    Camera cam = sphericalCamera(SphericalMapping::Equirectangular, 80, 40);
    expectDir(cam, {0, 20}, {1, 0, 0});
    expectDir(cam, {20, 20}, {0, 0, 1});
    expectDir(cam, {40, 20}, {-1, 0, 0});
    expectDir(cam, {60, 20}, {0, 0, -1});
    expectDir(cam, {13, 0}, {0, 1, 0});
    expectDir(cam, {57, 40}, {0, -1, 0});
    // theta = phi = pi/4.
    const float h = std::sqrt(0.5f);
    expectDir(cam, {10, 10}, {0.5f, h, 0.5f});
}

// The camera transform carries the origin and the directions (normalised even when it scales).
TEST(SphericalCamera, WorldFromCameraAndUnitLength) {
    Transform T = Transform::translate({1, 2, 3}) * Transform::rotate(90, {0, 1, 0}) * Transform::scale({2, 2, 2});
    for (SphericalMapping m : {SphericalMapping::EqualArea, SphericalMapping::Equirectangular}) {
        Camera local = sphericalCamera(m, 32, 32), world = sphericalCamera(m, 32, 32, T);
        Rng rng(5);
        float worst = 0;
        for (int i = 0; i < 1000; ++i) {
            // Also beyond the film's edge, where the pixel filter reaches.
            Vec2 pFilm(rng.uniform() * 40 - 4, rng.uniform() * 40 - 4);
            Ray a = local.generateRay({pFilm, {0.5f, 0.5f}}), b = world.generateRay({pFilm, {0.5f, 0.5f}});
            Vec3 want = normalize(T.vector(a.d));
            worst = std::max({worst, std::fabs(length(a.d) - 1), std::fabs(length(b.d) - 1), length(b.d - want)});
            ASSERT_NEAR(b.o.x, 1, 1e-6f);
            ASSERT_NEAR(b.o.y, 2, 1e-6f);
            ASSERT_NEAR(b.o.z, 3, 1e-6f);
        }
        std::printf("mapping %d: worst |len - 1| or world-direction error %.3g\n", int(m), worst);
        EXPECT_LT(worst, 1e-5f);
    }
}

// Every equal-area pixel sees the same solid angle. Exact count: by the mapping's mirror
// symmetries, exactly half of the pixel centres look forward (z > 0) and half right (x > 0).
// Chi-square: film points uniform over the film must give directions uniform over the
// sphere, i.e. uniform in height (Archimedes) and in azimuth around the up axis.
TEST(SphericalCamera, EqualAreaCoversTheSphereUniformly) {
    const int R = 64;
    Camera cam = sphericalCamera(SphericalMapping::EqualArea, R, R);
    int forward = 0, right = 0;
    for (int y = 0; y < R; ++y)
        for (int x = 0; x < R; ++x) {
            Vec3 d = cam.generateRay({{x + 0.5f, y + 0.5f}, {0.5f, 0.5f}}).d;
            forward += d.z > 0;
            right += d.x > 0;
        }
    std::printf("pixels looking forward %d, right %d, of %d\n", forward, right, R * R);
    EXPECT_EQ(forward, R * R / 2);
    EXPECT_EQ(right, R * R / 2);

    const int bands = 16, sectors = 16, n = 200 * bands * sectors;
    std::vector<int> count(bands * sectors, 0);
    Rng rng(17);
    for (int i = 0; i < n; ++i) {
        Vec3 d = cam.generateRay({{rng.uniform() * R, rng.uniform() * R}, {0.5f, 0.5f}}).d;
        int b = std::min(bands - 1, int((d.y + 1) / 2 * bands));
        float phi = std::atan2(d.z, d.x) + kPi;
        int s = std::min(sectors - 1, int(phi / (2 * kPi) * sectors));
        ++count[b * sectors + s];
    }
    double expected = double(n) / (bands * sectors), chi2 = 0;
    for (int c : count) chi2 += (c - expected) * (c - expected) / expected;
    // 255 degrees of freedom: mean 255, standard deviation sqrt(510) = 22.6; 4 sigma above.
    const double dof = bands * sectors - 1, limit = dof + 4 * std::sqrt(2 * dof);
    std::printf("chi-square %.1f (dof %.0f, limit %.1f)\n", chi2, dof, limit);
    EXPECT_LT(chi2, limit);
}

namespace {

// A camera at the origin looking along world +z (camera space = world space), box filter.
std::string sphericalScene(const std::string& cameraParams, int xRes, int yRes, const std::string& world) {
    return "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"spherical\" " + cameraParams + "\nFilm \"rgb\" \"integer xresolution\" " +
           std::to_string(xRes) + " \"integer yresolution\" " + std::to_string(yRes) +
           "\nPixelFilter \"box\"\nSampler \"independent\"\nWorldBegin\n" + world;
}

}  // namespace

// A constant environment seen through the spherical camera is that colour in every pixel,
// with the default (gaussian) filter whose samples reach beyond the film's edge. The shutter
// interval still sets the imaging ratio (pbrt-v4 reads it for every camera type); the lens
// parameters are accepted and ignored. In spectral mode, where each pixel carries its
// wavelengths' noise: every pixel is bit for bit that of a perspective camera (whose every
// sample sees the sky, with weight 1, from the same sample dimensions), and the image mean is
// the sky through the sensor (its standard error from independent renders: the filter spreads
// each sample over several pixels, which are therefore not independent).
TEST(SphericalCamera, ConstantEnvironmentFillsEveryPixel) {
    const bool spectral = defaultSpectral();
    struct Case { const char* params; float scale; const char* perspective; };
    for (Case c : {Case{"", 1.0f, ""}, Case{"\"string mapping\" \"equirectangular\"", 1.0f, ""},
                   Case{"\"float shutterclose\" 0.5 \"float lensradius\" 0.1 \"float focaldistance\" 3", 0.5f,
                        "\"float shutterclose\" 0.5"}}) {
        auto sceneWith = [](const std::string& camera) {
            return "LookAt 0 0 0  0 0 1  0 1 0\nCamera " + camera +
                   "\nFilm \"rgb\" \"integer xresolution\" 24 \"integer yresolution\" 16\n"
                   "WorldBegin\nLightSource \"infinite\" \"rgb L\" [0.2 0.5 0.9]\n";
        };
        const std::string scene = sceneWith("\"spherical\" " + std::string(c.params));
        if (spectral) {
            SCOPED_TRACE(c.params);
            RenderResult r = renderString(scene, 4);
            RenderResult p = renderString(sceneWith("\"perspective\" " + std::string(c.perspective)), 4);
            EXPECT_EQ(comparePixels(r.image, p.image).differ, 0);
            const BlockMeans b = blockMeans(scene, "path", 64, 12, 1);
            RegionStats m;
            for (int k = 0; k < 3; ++k) {
                m.mean[k] = b.channelMean[k];
                m.stdErr[k] = b.channelStdErr[k];
            }
            const float s = c.scale;
            expectSpectralMean(m, exactPixel(true, [s](double L) { return s * L; }, emission({0.2f, 0.5f, 0.9f})), c.params);
            continue;
        }
        RenderResult r = renderString(scene, 4);
        float worst = 0;
        for (int y = 0; y < r.image.height; ++y)
            for (int x = 0; x < r.image.width; ++x) {
                Spectrum v = r.image.get(x, y);
                worst = std::max({worst, std::fabs(v[0] - 0.2f * c.scale), std::fabs(v[1] - 0.5f * c.scale),
                                  std::fabs(v[2] - 0.9f * c.scale)});
            }
        std::printf("camera [%s]: worst pixel deviation %.3g\n", c.params, worst);
        EXPECT_LT(worst, 1e-5f);
    }
}

// A black sphere straight ahead (half-angle asin 0.4) under a white sky. Where it appears:
// bottom-middle (equal-area) or a quarter across the middle row (equirectangular); the
// pixels looking up see the sky: 1 in RGB mode, in spectral mode (each pixel with its
// wavelengths' noise) bit for bit the pixel of the sky alone. The equal-area image's mean is
// 1 - Omega / 4 pi of the sky's exactly in expectation (uniform film -> uniform sphere),
// Omega = 2 pi (1 - sqrt(1 - 0.4^2)).
TEST(SphericalCamera, BlackSphereAheadUnderWhiteSky) {
    const bool spectral = defaultSpectral();
    const std::string sky = "LightSource \"infinite\"\n";
    const std::string world = sky + "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n"
                                    "Translate 0 0 5\nShape \"sphere\" \"float radius\" 2\n";
    // Pixel (x, y) sees the sky alone.
    auto expectSky = [&](const Image& img, const Image& skyAlone, int x, int y) {
        if (spectral) EXPECT_EQ(img.get(x, y)[1], skyAlone.get(x, y)[1]) << x << "," << y;
        else EXPECT_NEAR(img.get(x, y)[1], 1.0f, 1e-5f) << x << "," << y;
    };
    {
        const std::string camera = "";
        RenderResult r = renderString(sphericalScene(camera, 32, 32, world), 4);
        const Image skyAlone = renderString(sphericalScene(camera, 32, 32, sky), 4).image;
        EXPECT_NEAR(r.image.get(16, 31)[1], 0.0f, 1e-6f);  // forward
        EXPECT_NEAR(r.image.get(15, 31)[1], 0.0f, 1e-6f);
        expectSky(r.image, skyAlone, 16, 16);  // up
        expectSky(r.image, skyAlone, 16, 0);   // backward
    }
    {
        const std::string camera = "\"string mapping\" \"equirectangular\"";
        RenderResult r = renderString(sphericalScene(camera, 32, 16, world), 4);
        const Image skyAlone = renderString(sphericalScene(camera, 32, 16, sky), 4).image;
        EXPECT_NEAR(r.image.get(8, 8)[1], 0.0f, 1e-6f);  // forward
        EXPECT_NEAR(r.image.get(7, 7)[1], 0.0f, 1e-6f);
        expectSky(r.image, skyAlone, 24, 8);  // backward
        expectSky(r.image, skyAlone, 8, 0);   // up
    }
    BlockMeans b = blockMeans(sphericalScene("", 32, 32, world), "path", 8, 12, 1);
    // The sky's luminance: 1 in RGB mode, the default light's through the sensor in spectral.
    const auto skyRGB = exactPixel(spectral, itself, emission({1, 1, 1}));
    const double skyY = 0.2126 * skyRGB[0] + 0.7152 * skyRGB[1] + 0.0722 * skyRGB[2];
    const double expected = skyY * (1 - (1 - std::sqrt(1 - 0.16)) / 2);
    std::printf("image mean %.5f +- %.5f, expected %.5f (%.2f sigma)\n", b.imageMean, b.imageStdErr, expected,
                (b.imageMean - expected) / b.imageStdErr);
    EXPECT_LT(std::fabs(b.imageMean - expected), 4 * b.imageStdErr);
}

// Light tracing connects every light path to the lens and Veach's mutations move the lens
// vertex: the spherical camera has no importance function (nor does pbrt-v4's), so they are
// refused; BDPT and the primary-sample chains run without their t = 1 strategies.
TEST(SphericalCamera, OnlyLightTracingAndMltAreRefused) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(sphericalScene("", 8, 8, "LightSource \"infinite\"\n"), ".", "<test>");
    auto scene = buildScene(desc);
    EXPECT_FALSE(scene->camera().hasImportance());
    for (const char* name : {"light", "mlt"}) {
        try {
            createIntegrator(name, *scene);
            ADD_FAILURE() << name << " accepted a spherical camera";
        } catch (const InputError& e) {
            std::printf("%s: %s\n", name, e.what());
            EXPECT_NE(std::string(e.what()).find("needs a perspective camera"), std::string::npos);
        }
    }
    for (const char* name : {"path", "bdpt", "pssmlt", "mmlt"}) EXPECT_NO_THROW(createIntegrator(name, *scene)) << name;
}

// An unknown mapping is an error at the parameter's location.
TEST(SphericalCamera, UnknownMappingIsAnError) {
    setWarningsQuiet(true);
    SceneDescription desc =
        parseSceneString(sphericalScene("\"string mapping\" \"fisheye\"", 8, 8, "LightSource \"infinite\"\n"), ".", "<test>");
    try {
        buildScene(desc);
        ADD_FAILURE() << "mapping \"fisheye\" accepted";
    } catch (const InputError& e) {
        std::printf("%s\n", e.what());
        EXPECT_NE(std::string(e.what()).find("<test>:2:"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("unknown \"mapping\" \"fisheye\""), std::string::npos);
    }
}
