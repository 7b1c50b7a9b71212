// The lens perturbation's transition density, against the geometry it must follow. A
// perspective camera maps film to a plane facing it linearly (s units of the plane per pixel),
// so the proposals' new vertices, drawn from the film offset's
// density K(r) = 1 / (2 pi r^2 ln(r2 / r1)) on r1 < r < r2, cover an annulus of the plane of
// area pi (r2^2 - r1^2) s^2. The mean of 1 / T(x -> y) over the proposals, T being the area
// density the mutation claims (K times its Jacobian from film to plane), must be that area:
// a wrong Jacobian (a missing cosine or distance) fails it. And the ratio the mutation
// returns must be T(y -> x) / T(x -> y). (Through a specular chain T is the pseudo-density
// of the unit-delta convention that f shares, not the plane's area density: a flat mirror
// at 45 degrees gave 0.64 of the annulus' area, as cos / (d1^2 d2^2) against 1 / (d1 + d2)^2
// predicts; veach_perturbation_chi_test.cpp checks T through mirrors in that measure.)
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "mc/estimator.h"
#include "render_helpers.h"
#include "transport/mlt/veach/veach_mlt.h"

using namespace ps;
using namespace ps::test;

namespace {

constexpr int kRes = 64;
constexpr double kFov = 40;  // degrees

// A film point near the centre: the path through it, from a point light that sees the plane.
struct PathSetup {
    std::unique_ptr<Scene> scene;
    std::unique_ptr<VeachMLTIntegrator> integrator;
    MltPath x;
    Vec2 rasterX;
};

PathSetup makePath(const std::string& world, int cameraVertices) {
    PathSetup s;
    setWarningsQuiet(true);
    const std::string text = "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ " +
                             std::to_string(kFov) + " ]\nFilm \"rgb\" \"integer xresolution\" [ " + std::to_string(kRes) +
                             " ] \"integer yresolution\" [ " + std::to_string(kRes) + " ]\nPixelFilter \"box\"\nWorldBegin\n" + world;
    s.scene = buildScene(parseSceneString(text, ".", "<test>"));
    s.integrator = std::make_unique<VeachMLTIntegrator>(*s.scene, 5, MetropolisParams{});
    const PathSpace& space = s.integrator->space();
    static ScratchBuffer arena;
    PathStats stats;
    // The camera side through the film's centre pixel, then the point light.
    std::vector<MltVertex> camera(1);
    Ray ray = space.cameraRay(Vec2(kRes / 2, kRes / 2), Vec2(0.5f, 0.5f), 0.0f, {}, &camera[0]);
    Rng rng(7);
    while (int(camera.size()) < cameraVertices) {
        MltVertex v;
        EXPECT_TRUE(space.trace(ray, {}, arena, stats, v));
        camera.push_back(v);
        if (int(camera.size()) < cameraVertices) {
            EXPECT_TRUE(space.scatter(camera, TransportMode::Radiance, rng, ray));
        }
    }
    std::vector<MltVertex> light;
    EXPECT_TRUE(space.walk(light, 1, TransportMode::Importance, 0.0f, {}, rng, arena, stats));
    s.x = light;
    s.x.insert(s.x.end(), camera.rbegin(), camera.rend());
    EXPECT_GT(space.contribution(s.x, &s.rasterX).luminance(), 0.0f);
    return s;
}

// T(x -> y) for the lens perturbation, by the formula the test checks against geometry: the
// film offset's density times the film-to-area Jacobian of the retraced vertices.
double density(const PathSetup& s, const MltPath& from, const MltPath& to) {
    const PathSpace& space = s.integrator->space();
    Vec2 rFrom, rTo;
    space.contribution(from, &rFrom);
    space.contribution(to, &rTo);
    const double r = std::hypot(double(rTo.x - rFrom.x), double(rTo.y - rFrom.y));
    const double r1 = 0.1, r2 = s.integrator->perturbations().r2();
    if (!(r > r1 && r < r2)) return 0;
    const double K = 1 / (2 * kPi * r * r * std::log(r2 / r1));
    const double filmArea = double(space.filmSize().x) * double(space.filmSize().y);
    const int k = int(to.size()) - 1;
    double jacobian = filmArea;
    for (int i = k - 1; i >= 1; --i) jacobian *= space.cameraDensity(to, i, PathSpace::Lobes::Forced);
    return K * jacobian;
}

// The area of the plane through (0, 0, 3) with normal (sin tilt, 0, -cos tilt) that the
// camera (at the origin, looking along +z) sees through the annulus r1 < r < r2 around the
// film's centre: the film-to-plane map's Jacobian, by finite differences of the ray-plane
// hit, integrated in polar coordinates (a check independent of the renderer's densities).
double annulusArea(double tiltDeg, double r1, double r2) {
    const double tilt = tiltDeg * kPi / 180, scale = std::tan(kFov / 2 * kPi / 180);
    const double nx = std::sin(tilt), nz = -std::cos(tilt), c = nz * 3;
    auto hit = [&](double u, double v) {  // film offset in pixels from the centre
        const double dx = 2 * u / kRes * scale, dy = 2 * v / kRes * scale;
        const double t = c / (nx * dx + nz);
        return std::array<double, 3>{t * dx, t * dy, t};
    };
    auto jacobian = [&](double u, double v) {
        const double h = 1e-3;
        auto a = hit(u + h, v), b = hit(u - h, v), e = hit(u, v + h), f = hit(u, v - h);
        const double pu[3] = {(a[0] - b[0]) / (2 * h), (a[1] - b[1]) / (2 * h), (a[2] - b[2]) / (2 * h)};
        const double pv[3] = {(e[0] - f[0]) / (2 * h), (e[1] - f[1]) / (2 * h), (e[2] - f[2]) / (2 * h)};
        const double cx = pu[1] * pv[2] - pu[2] * pv[1], cy = pu[2] * pv[0] - pu[0] * pv[2], cz = pu[0] * pv[1] - pu[1] * pv[0];
        return std::sqrt(cx * cx + cy * cy + cz * cz);
    };
    double area = 0;
    const int nr = 400, na = 400;
    for (int i = 0; i < nr; ++i)
        for (int j = 0; j < na; ++j) {
            const double r = r1 + (r2 - r1) * (i + 0.5) / nr, a = 2 * kPi * (j + 0.5) / na;
            area += jacobian(r * std::cos(a), r * std::sin(a)) * r * (r2 - r1) / nr * 2 * kPi / na;
        }
    return area;
}

void expectAnnulusArea(const PathSetup& s, double tiltDeg) {
    const Perturbations& p = s.integrator->perturbations();
    ASSERT_TRUE(p.lensApplies(s.x));
    const double exact = annulusArea(tiltDeg, 0.1, p.r2());
    ScratchBuffer arena;
    PathStats stats;
    Rng rng(11);
    RunningStats inverse;
    int failed = 0, ratioOff = 0;
    MltPath y;
    for (int n = 0; n < 200000; ++n) {
        double ratio = 0;
        if (!p.lens(s.x, s.rasterX, rng, arena, stats, y, &ratio)) {
            ++failed;
            inverse.add(0);
            continue;
        }
        const double forward = density(s, s.x, y), backward = density(s, y, s.x);
        inverse.add(forward > 0 ? 1 / forward : 0);
        if (!(std::fabs(ratio - backward / forward) <= 1e-3 * ratio)) ++ratioOff;
    }
    const double z = (inverse.mean() - exact) / inverse.standardError();
    std::printf("[ lens perturbation ] annulus area %.6g +- %.2g, exact %.6g (%.2f sigma; 4 sigma = %.2f%%), %d failed, "
                "%d ratios off\n",
                inverse.mean(), inverse.standardError(), exact, z, 400 * inverse.standardError() / exact, failed, ratioOff);
    EXPECT_LT(std::fabs(z), 4.0);
    EXPECT_LT(4 * inverse.standardError(), 0.02 * exact) << "too noisy";
    // A few in 10^5 lie at the offset's bounds r1, r2 once the film point is rounded to float
    // and found again from the path, where the test's density steps to 0.
    EXPECT_LE(failed, 20);
    EXPECT_LE(ratioOff, 20);
}

}  // namespace

// The plane facing the camera at distance 3 (path L D E), and the same plane tilted by 60
// degrees about the vertical (its Jacobian then varies over the annulus, so that a missing
// cosine or a ratio taken as 1 shows).
TEST(VeachLensPerturbation, DensityCoversTheAnnulusOfAPlane) {
    PathSetup s = makePath(R"(
        LightSource "point" "rgb I" [ 1 1 1 ] "point3 from" [ 0.3 0.2 1 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "bilinearmesh" "point3 P" [ -5 -5 3   5 -5 3   -5 5 3   5 5 3 ]
    )", 2);
    expectAnnulusArea(s, 0);
}

TEST(VeachLensPerturbation, DensityCoversTheAnnulusOfATiltedPlane) {
    // Points (x, y, 3 + x tan 60).
    PathSetup s = makePath(R"(
        LightSource "point" "rgb I" [ 1 1 1 ] "point3 from" [ 0.3 0.2 1 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "bilinearmesh" "point3 P" [ -1.5 -5 0.40192   1.5 -5 5.59808   -1.5 5 0.40192   1.5 5 5.59808 ]
    )", 2);
    expectAnnulusArea(s, 60);
}
