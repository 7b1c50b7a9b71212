// The t = 0 strategy (transport/lens_hits.h, thesis §10.2): light subpaths that reach a thin
// lens by themselves. A point light seen in a flat mirror through a thin lens is sampled by
// no other strategy (thesis §1.1); its image mean has a closed form from the lens importance
// (docs/unsampled-paths.md derives it), and a small sphere light of the same
// intensity, which the camera subpaths also find, renders the same mean by BDPT and by path
// tracing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

// The camera at the origin looks down -z through a lens of radius r focused at z = -2; the
// mirror (reflectance 1: F = 0.9999 at every angle, materials.cpp) fills the view at z = -zm;
// the light sits behind the lens at z = +zl, where the camera does not see it, so its mirror
// image is on the axis at D = 2 zm + zl in front of the lens.
constexpr double kLensRadius = 0.25, kMirror = 0.375, kLightZ = 0.25, kFov = 40, kI = 1;
constexpr int kRes = 48;

std::string header(const char* integrator) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "LookAt 0 0 0  0 0 -1  0 1 0\n"
                  "Camera \"perspective\" \"float fov\" [ %g ] \"float lensradius\" [ %g ] \"float focaldistance\" [ 2 ]\n"
                  "Film \"rgb\" \"integer xresolution\" [ %d ] \"integer yresolution\" [ %d ]\n"
                  "PixelFilter \"box\"\nSampler \"independent\"\n"
                  "Integrator \"%s\" \"integer maxdepth\" [ 3 ]\nWorldBegin\n"
                  "AttributeBegin\nMaterial \"conductor\" \"rgb reflectance\" [ 1 1 1 ] \"float roughness\" [ 0 ]\n"
                  "Shape \"trianglemesh\" \"point3 P\" [ -4 -4 %g  4 -4 %g  4 4 %g  -4 4 %g ] "
                  "\"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n",
                  kFov, kLensRadius, kRes, kRes, integrator, -kMirror, -kMirror, -kMirror, -kMirror);
    return text;
}

std::string pointLightScene(const char* integrator) {
    char light[128];
    std::snprintf(light, sizeof light, "LightSource \"point\" \"rgb I\" [ %g %g %g ] \"point3 from\" [ 0 0 %g ]\n", kI,
                  kI, kI, kLightZ);
    return header(integrator) + light;
}

// A black sphere of radius rho and radiance L = I / (pi rho^2) sends intensity I every way
// (its projected area is pi rho^2 from anywhere), and the irradiance it gives a point that
// sees all of it is that of a point light at its centre. The image weighs its directions by
// W_e ~ 1 / cos^4, larger off the axis: a sphere subtending alpha = rho / D gives some
// (3/4) alpha^2 more (rho = 0.1: +0.75%, measured +1.0%; rho = 0.03: +0.07%).
std::string sphereLightScene(const char* integrator, double rho) {
    char light[320];
    const double L = kI / (M_PI * rho * rho);
    std::snprintf(light, sizeof light,
                  "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ %g %g %g ]\n"
                  "Material \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\nTranslate 0 0 %g\n"
                  "Shape \"sphere\" \"float radius\" [ %g ]\nAttributeEnd\n",
                  L, L, L, kLightZ, rho);
    return header(integrator) + light;
}

// The image mean: the irradiance R I cos(theta) / d^2 that the mirror image sends each lens
// point, times W_e = 1 / (A lensArea cos^4 theta) (camera.h; A the film's area at z = 1),
// integrated over the lens: R I / (A pi r^2) * 2 pi / (3 D^3) * ((D^2 + r^2)^(3/2) - D^3).
double exactMean() {
    const double r = kLensRadius, D = 2 * kMirror + kLightZ, R = 0.9999;
    const double t = std::tan(kFov * M_PI / 360), A = 4 * t * t;
    return R * kI / (A * M_PI * r * r) * 2 * M_PI / (3 * D * D * D) * (std::pow(D * D + r * r, 1.5) - D * D * D);
}

struct Estimate {
    double mean = 0, sigma = 0;
};

// The mean of independent renders (fixed seeds) and its standard error measured across them.
Estimate measure(const std::string& scene, const char* integrator, int spp, int renders, uint64_t seed0) {
    const BlockMeans b = blockMeans(scene, integrator, spp, renders, 1, seed0, false);
    std::printf("  %-6s %.5f +- %.5f (%d renders of %d spp)\n", integrator, b.imageMean, b.imageStdErr, renders, spp);
    return {b.imageMean, b.imageStdErr};
}

}  // namespace

// BDPT (t = 0 alone samples these paths) and light tracing against the closed form, within
// 4 sigma, where 4 sigma is below 2% of the answer.
TEST(LensHits, PointLightInAMirrorThroughAThinLens) {
    const double exact = exactMean();
    std::printf("  exact %.5f\n", exact);
    for (const char* integrator : {"bdpt", "light"}) {
        const Estimate e = measure(pointLightScene(integrator), integrator, 64, 24, 300);
        EXPECT_LT(4 * e.sigma, 0.02 * exact) << integrator;
        EXPECT_NEAR(e.mean, exact, 4 * e.sigma) << integrator << ": " << (e.mean - exact) / e.sigma << " sigma";
    }
    // Path tracing cannot find the point light: the image is black.
    const Estimate path = measure(pointLightScene("path"), "path", 1, 2, 300);
    EXPECT_EQ(path.mean, 0.0);
}

// The point light replaced by a small sphere light of the same intensity: BDPT (t = 0 weighted
// against the camera subpaths that find the sphere in the mirror) and path tracing agree
// with the point light's t = 0 image within 4 sigma.
TEST(LensHits, SphereLightAgreesWithThePointLight) {
    const Estimate point = measure(pointLightScene("bdpt"), "bdpt", 64, 24, 300);
    for (const char* integrator : {"bdpt", "path"}) {
        const Estimate e = measure(sphereLightScene(integrator, 0.03), integrator, 64, 24, 500);
        const double sigma = std::hypot(e.sigma, point.sigma);
        EXPECT_NEAR(e.mean, point.mean, 4 * sigma) << integrator << ": " << (e.mean - point.mean) / sigma << " sigma";
    }
}
