// Camera "realistic" with pbrt-v4's semantics: the lens description parser, focusing by the
// thick-lens approximation against the lensmaker's formulas, the image irradiance weight
// against its exact integral over the exit pupil, sharp and defocused images, blocked rays,
// and the refusals and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "camera/aperture_mask.h"
#include "camera/lens_system.h"
#include "mc/rng.h"
#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

const std::string kLensDir = std::string(PATHSPACE_SOURCE_DIR) + "/tests/data/lenses/";
const std::string kBiconvex = kLensDir + "biconvex.dat";

// The biconvex test lens: radii +-50 mm, 5 mm of index 1.5, stop 2 mm behind it.
constexpr double kR1 = 0.05, kR2 = -0.05, kThick = 0.005, kN = 1.5, kStopGap = 0.002;

LensSystem biconvexLens(float focusDistance, float stopDiameter, int xRes = 64, int yRes = 64,
                        int pupilSamples = 1 << 14, std::shared_ptr<const ApertureMask> mask = nullptr) {
    LensSystem::Params p;
    p.mask = std::move(mask);
    p.interfaces = readLensFile(kBiconvex);
    p.apertureDiameter = stopDiameter;
    p.focusDistance = focusDistance;
    p.xRes = xRes;
    p.yRes = yRes;
    p.pupilSamplesPerSegment = pupilSamples;
    return LensSystem(p);
}

// Thick-lens optics of the biconvex lens from the lensmaker's formulas: the distance s
// from the rear vertex to the film that images the plane at distance D from the film.
double analyticRearVertexToFilm(double D) {
    double invF = (kN - 1) * (1 / kR1 - 1 / kR2 + (kN - 1) * kThick / (kN * kR1 * kR2));
    double f = 1 / invF;
    double h1 = -f * (kN - 1) * kThick / (kN * kR2);  // front principal plane behind the front vertex
    double h2 = -f * (kN - 1) * kThick / (kN * kR1);  // rear principal plane behind the rear vertex (< 0)
    // Image distance v = s - h2, object distance u = D - (s + thick - h1): find s with
    // 1/u + 1/v = 1/f by bisection on the branch where the film is beyond the focal point.
    auto g = [&](double s) { return 1 / (D - (s + kThick - h1)) + 1 / (s - h2) - invF; };
    double lo = f + h2 + 1e-9, hi = f + h2 + 0.5 * (D - 2 * f);
    for (int i = 0; i < 200; ++i) {
        double mid = (lo + hi) / 2;
        (g(mid) > 0 ? lo : hi) = mid;
    }
    return (lo + hi) / 2;
}

// A camera at the origin looking along +z (camera space = world space).
std::string realisticScene(const std::string& cameraParams, int res, const std::string& film,
                           const std::string& world, const std::string& sampler = "independent") {
    return "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"realistic\" \"string lensfile\" \"" + kBiconvex + "\" " +
           cameraParams + "\nFilm \"rgb\" \"integer xresolution\" " + std::to_string(res) +
           " \"integer yresolution\" " + std::to_string(res) + " " + film + "\nPixelFilter \"box\"\nSampler \"" +
           sampler + "\"\nWorldBegin\n" + world;
}

std::string writeTemp(const std::string& name, const std::string& text) {
    std::filesystem::path p = std::filesystem::temp_directory_path() / name;
    std::ofstream(p) << text;
    return p.string();
}

}  // namespace

// Millimetres become metres, diameters radii; a zero radius is the stop; '#' comments, tabs
// and an index of 0 (air) are read as pbrt-v4 reads them.
TEST(RealisticCamera, LensFileUnitsAndStop) {
    std::vector<LensInterface> d = readLensFile(kLensDir + "dgauss.50mm.dat");
    ASSERT_EQ(d.size(), 11u);
    EXPECT_FLOAT_EQ(d[0].curvatureRadius, 0.029475f);
    EXPECT_FLOAT_EQ(d[0].thickness, 0.00376f);
    EXPECT_FLOAT_EQ(d[0].eta, 1.67f);
    EXPECT_FLOAT_EQ(d[0].apertureRadius, 0.0126f);
    int stops = 0;
    for (size_t i = 0; i < d.size(); ++i) stops += d[i].isStop();
    EXPECT_EQ(stops, 1);
    EXPECT_TRUE(d[5].isStop());
    EXPECT_FLOAT_EQ(d[5].eta, 1.0f);  // 0 in the file: air
    EXPECT_FLOAT_EQ(d[5].apertureRadius, 0.00855f);
    EXPECT_FLOAT_EQ(d[10].curvatureRadius, -0.03973f);
    EXPECT_FLOAT_EQ(d[10].thickness, 0.0f);

    // "aperturediameter" (here 4 mm) sets the stop; a larger one is clamped to the stop's.
    LensSystem small = biconvexLens(1.0f, 0.004f);
    EXPECT_FLOAT_EQ(small.interfaces()[2].apertureRadius, 0.002f);
    EXPECT_FALSE(small.apertureClamped());
    LensSystem big = biconvexLens(1.0f, 0.05f);
    EXPECT_FLOAT_EQ(big.interfaces()[2].apertureRadius, 0.005f);
    EXPECT_TRUE(big.apertureClamped());
    EXPECT_FLOAT_EQ(big.interfaces()[0].apertureRadius, 0.01f);  // lens elements keep theirs
}

// Malformed descriptions name the file and the line.
TEST(RealisticCamera, LensFileErrors) {
    struct Case { const char* text; const char* expect; };
    for (Case c : {Case{"# lens\n50 5 1.5 20\n-50 2 1 x20\n", "bad.dat:3: lens description: \"x20\" is not a number"},
                   Case{"50 5 1.5 20\n\n0 50 0\n", "bad.dat:3: lens description: 7 numbers, not a multiple of four"},
                   Case{"# only a comment\n", "bad.dat: lens description has no interfaces"},
                   Case{"50 -5 1.5 20\n", "bad.dat:1: lens description: negative thickness"},
                   Case{"50 5 1.5 0\n", "bad.dat:1: lens description: the aperture diameter must be positive"}}) {
        try {
            parseLensDescription(c.text, "bad.dat");
            ADD_FAILURE() << "accepted: " << c.text;
        } catch (const InputError& e) {
            std::printf("%s\n", e.what());
            EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
        }
    }
}

// Focusing: the film distance the thick-lens approximation gives equals the lensmaker's
// formula's, and rays from the axis point at the focus distance through ever smaller zones
// of the lens converge ever nearer the film plane (spherical aberration grows as h^2, so
// the crossings extrapolated to h = 0 give the paraxial image).
TEST(RealisticCamera, FocusMatchesTheLensEquation) {
    for (float D : {0.5f, 1.0f, 4.0f}) {
        LensSystem lens = biconvexLens(D, 0.01f);
        double s = lens.rearZ() + kStopGap, want = analyticRearVertexToFilm(D);
        std::printf("D = %.2f m: rear vertex to film %.7f m, lensmaker %.7f m (diff %.2g m)\n", D, s, want, s - want);
        EXPECT_NEAR(s, want, 1e-6);

        // Axis crossings behind the lens of rays from (0, 0, D) aimed at height h on the
        // front vertex's plane: z(h) = z0 + k h^2, least squares.
        double sh2 = 0, sh4 = 0, sz = 0, szh2 = 0;
        int n = 0;
        for (float h : {0.5e-3f, 1e-3f, 1.5e-3f, 2e-3f, 2.5e-3f, 3e-3f}) {
            Ray out;
            ASSERT_TRUE(lens.traceFromScene(Ray{{0, 0, D}, {h, 0, lens.frontZ() - D}}, &out));
            double z = out.o.z - double(out.o.x) * out.d.z / out.d.x;
            double h2 = double(h) * h;
            sh2 += h2; sh4 += h2 * h2; sz += z; szh2 += z * h2;
            ++n;
        }
        double k = (n * szh2 - sh2 * sz) / (n * sh4 - sh2 * sh2), z0 = (sz - k * sh2) / n;
        std::printf("  paraxial image at z = %.3g m from the film (aberration %.3g m per mm^2 of zone)\n", z0, k * 1e-6);
        EXPECT_NEAR(z0, 0.0, 2e-6);
    }
}

namespace {

// E(h): the image irradiance weight at film distance h from the axis for a uniform radiance
// of 1, the exact integral over the circular stop of radius r at distance z (the exit
// pupil of the test lens, whose stop is its rear element) of cos^4(theta) / z^2.
double pupilIntegral(double h, double r, double z) {
    const int nr = 120, nphi = 240;
    double sum = 0;
    for (int i = 0; i < nr; ++i) {
        double rho = (i + 0.5) / nr * r;
        for (int j = 0; j < nphi; ++j) {
            double phi = (j + 0.5) / nphi * 2 * kPi;
            double dx = rho * std::cos(phi) - h, dy = rho * std::sin(phi);
            double d2 = z * z + dx * dx + dy * dy;
            sum += z * z / (d2 * d2) * rho;
        }
    }
    return sum * (r / nr) * (2 * kPi / nphi);
}

// E(h) tabulated over the film's half diagonal (35 mm film) and linearly interpolated.
struct PupilWeight {
    static constexpr int kN = 400;
    static constexpr double kHMax = 0.0175;
    std::vector<double> table;
    PupilWeight(double r, double z) : table(kN + 1) {
        for (int i = 0; i <= kN; ++i) table[size_t(i)] = pupilIntegral(kHMax * i / kN, r, z);
    }
    double operator()(double h) const {
        double x = std::min(h / kHMax, 1.0) * kN;
        int i = std::min(int(x), kN - 1);
        return table[size_t(i)] + (x - i) * (table[size_t(i) + 1] - table[size_t(i)]);
    }
    double at(const LensSystem& lens, Vec2 pRaster) const { return (*this)(length(lens.filmPoint(pRaster))); }
};

}  // namespace

// Radiometry: a uniform white environment seen through the lens. Each pixel is, in
// expectation, E(|h|) at its film point (pbrt-v4's weight cos^4 / (pdf rearZ^2) integrated
// over the exit pupil): pi r^2 / (z^2 + r^2) at the centre, falling off towards the corners.
// The residual pixel - E over every pixel has mean 0; its spread gives the standard error.
TEST(RealisticCamera, UniformEmitterFollowsTheCos4Weight) {
    const int res = 64, spp = 64;
    const float stop = 0.01f;
    RenderResult img = renderString(
        realisticScene("\"float aperturediameter\" 10 \"float focusdistance\" 1", res, "",
                       "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"),
        spp);
    LensSystem lens = biconvexLens(1.0f, stop, res, res);
    const double r = stop / 2, z = lens.rearZ();
    const PupilWeight E(r, z);
    const std::vector<double>& table = E.table;
    std::printf("centre: closed form pi r^2/(z^2+r^2) = %.7f, quadrature %.7f\n", kPi * r * r / (z * z + r * r),
                table[0]);
    EXPECT_NEAR(table[0], kPi * r * r / (z * z + r * r), 1e-6 * table[0]);

    double s = 0, s2 = 0, centre = 0, corner = 0;
    int n = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            Vec3 p = lens.filmPoint({x + 0.5f, y + 0.5f});
            double v = img.image.get(x, y)[1];
            ASSERT_TRUE(std::isfinite(v));
            double d = v - E(length(p));
            s += d;
            s2 += d * d;
            ++n;
            if ((x == res / 2 || x == res / 2 - 1) && (y == res / 2 || y == res / 2 - 1)) centre += v / 4;
            if ((x == 0 || x == res - 1) && (y == 0 || y == res - 1)) corner += v / 4;
        }
    double mean = s / n, sigma = std::sqrt((s2 / n - mean * mean) / (n - 1));
    Vec3 pCentre = lens.filmPoint({res / 2.0f + 0.5f, res / 2.0f + 0.5f}), pCorner = lens.filmPoint({0.5f, 0.5f});
    std::printf("centre pixels %.6f (E %.6f), corner pixels %.6f (E %.6f)\n", centre, E(length(pCentre)), corner,
                E(length(pCorner)));
    std::printf("mean residual %.3g, sigma %.3g (%.2f sigma; relative to the centre %.2g)\n", mean, sigma,
                mean / sigma, sigma / table[0]);
    EXPECT_LT(std::fabs(mean), 4 * sigma);
    EXPECT_LT(sigma, 2e-3 * table[0]);  // the test resolves the weight to a fraction of a percent
    EXPECT_LT(corner, 0.85 * centre);   // vignetting: cos^4 of 19 degrees is 0.80
}

namespace {

// A plane at z = 1 m under a white sky with a checkerboard of 8 x 1 squares (vertical
// stripes 62.5 mm wide, reflectance 1 and 0), seen through the test lens at f/5 focused at
// D. Returns how many column means (each over all rows, so noise averages out) of the
// reflectance in the middle 32 columns lie between 0.15 and 0.85: the pixels on blurred edges.
int greyColumns(float D) {
    const int res = 64;
    const std::string world =
        "LightSource \"infinite\"\n"
        "Texture \"checks\" \"spectrum\" \"checkerboard\" \"float uscale\" 8 \"float vscale\" 1 "
        "\"rgb tex1\" [1 1 1] \"rgb tex2\" [0 0 0]\n"
        "Material \"diffuse\" \"texture reflectance\" \"checks\"\n"
        "Shape \"trianglemesh\" \"point3 P\" [-0.25 -0.25 1  0.25 -0.25 1  0.25 0.25 1  -0.25 0.25 1] "
        "\"integer indices\" [0 1 2 0 2 3] \"point2 uv\" [0 0 1 0 1 1 0 1]\n";
    RenderResult r = renderString(
        realisticScene("\"float aperturediameter\" 10 \"float focusdistance\" " + std::to_string(D), res,
                       "", world),
        16);
    // Divided by the white sky's exact image (vignetting), pixels are the plane's reflectance.
    LensSystem lens = biconvexLens(D, 0.01f, res, res);
    const PupilWeight E(0.005, lens.rearZ());
    std::vector<double> col(res, 0.0);
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) col[size_t(x)] += r.image.get(x, y)[1] / E.at(lens, {x + 0.5f, y + 0.5f}) / res;
    // The middle half of the columns: the singlet's off-axis aberrations blur the sides.
    int mid = 0;
    for (int x = res / 4; x < res * 3 / 4; ++x) mid += col[size_t(x)] > 0.15 && col[size_t(x)] < 0.85;
    return mid;
}

}  // namespace

// Focused on the plane, the stripes' edges are sharp: the blur circle is far below a pixel,
// so only a column straddling an edge can be grey, at most one for each of the 3 or 4 edges
// in the middle 32 columns (stripes are 8.9 pixels wide). Focused at 0.5 m the blur circle
// is about 1.3 pixels wide, at 0.3 m about 4 pixels: more grey columns.
TEST(RealisticCamera, SharpAtTheFocusDistance) {
    int sharp = greyColumns(1.0f), soft = greyColumns(0.5f), blurred = greyColumns(0.3f);
    std::printf("grey columns of the middle 32: focused at 1 m %d, at 0.5 m %d, at 0.3 m %d\n", sharp, soft, blurred);
    EXPECT_LE(sharp, 4);
    EXPECT_GT(soft, sharp);
    EXPECT_GT(blurred, soft);
    EXPECT_GE(blurred, 2 * sharp + 4);
}

// A film far larger than the lens covers (2 m diagonal): its corners see no exit pupil and
// are black, exactly; no pixel is NaN; the middle still sees the sky.
TEST(RealisticCamera, BlockedRaysAreBlackNotNaN) {
    const int res = 32;
    RenderResult r = renderString(realisticScene("\"float aperturediameter\" 10 \"float focusdistance\" 1", res,
                                                 "\"float diagonal\" 2000", "LightSource \"infinite\"\n"),
                                  16);
    int black = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            Spectrum v = r.image.get(x, y);
            ASSERT_TRUE(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2])) << x << " " << y;
            black += v[1] == 0;
        }
    std::printf("%d of %d pixels black; middle pixel %.4g\n", black, res * res, r.image.get(res / 2, res / 2)[1]);
    for (Vec2 p : {Vec2(0, 0), Vec2(res - 1, 0), Vec2(0, res - 1), Vec2(res - 1, res - 1)})
        EXPECT_EQ(r.image.get(int(p.x), int(p.y))[1], 0.0f);
    EXPECT_GT(black, 4);
    EXPECT_GT(r.image.get(res / 2, res / 2)[1], 0.0f);
}

// Light tracing connects every light path to the lens and Veach's mutations move the lens
// vertex: the realistic camera has no importance function (nor does pbrt-v4's), so they are
// refused; BDPT and the primary-sample chains run without their t = 1 strategies.
TEST(RealisticCamera, OnlyLightTracingAndMltAreRefused) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(realisticScene("", 8, "", "LightSource \"infinite\"\n"), ".", "<test>");
    auto scene = buildScene(desc);
    EXPECT_FALSE(scene->camera().hasImportance());
    for (const char* name : {"light", "mlt"}) {
        try {
            createIntegrator(name, *scene);
            ADD_FAILURE() << name << " accepted a realistic camera";
        } catch (const InputError& e) {
            std::printf("%s: %s\n", name, e.what());
            EXPECT_NE(std::string(e.what()).find("needs a perspective camera"), std::string::npos);
        }
    }
    for (const char* name : {"path", "bdpt", "pssmlt", "mmlt"}) EXPECT_NO_THROW(createIntegrator(name, *scene)) << name;
}

// Scene errors are located at the Camera directive and name the lens file (and its line).
TEST(RealisticCamera, SceneErrorsAreLocated) {
    setWarningsQuiet(true);
    const std::string bad = writeTemp("pathspace-bad-lens.dat", "50 5 1.5 20\n-50 2 1 20\n0 50 0 x\n");
    auto sceneWith = [](const std::string& params) {
        return "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"realistic\" " + params +
               "\nFilm \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n";
    };
    struct Case { std::string params, expect; };
    for (const Case& c : {Case{"\"string lensfile\" \"no-such-lens.dat\"", "no-such-lens.dat: cannot open lens file"},
                          Case{"\"string lensfile\" \"" + bad + "\"", "pathspace-bad-lens.dat:3: lens description: \"x\""},
                          Case{"", "no \"lensfile\" given"},
                          Case{"\"string lensfile\" \"" + kBiconvex + "\" \"float focusdistance\" 0.15",
                               "is too short for this lens"}}) {
        try {
            buildScene(parseSceneString(sceneWith(c.params), ".", "<test>"));
            ADD_FAILURE() << "accepted: " << c.params;
        } catch (const InputError& e) {
            std::printf("%s\n", e.what());
            EXPECT_NE(std::string(e.what()).find("<test>:2:1: error: "), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
        }
    }
    std::filesystem::remove(bad);
}

namespace {

// The exact weight integral of a mask over the stop of radius rr at distance z, seen from
// the film's centre: the sum over texels of value * cos^4 / z^2 * texel area (the bilinear
// lookup's hat functions each integrate to one texel).
double maskIntegral(const ApertureMask& mask, double rr, double z) {
    const double texel = 2 * rr / mask.width();
    double sum = 0;
    for (int y = 0; y < mask.height(); ++y)
        for (int x = 0; x < mask.width(); ++x) {
            double qx = -rr + (x + 0.5) * texel, qy = -rr + (y + 0.5) * texel, d2 = z * z + qx * qx + qy * qy;
            sum += mask.texel(x, y) * z * z / (d2 * d2) * texel * texel;
        }
    return sum;
}

}  // namespace

// Shaped apertures (pbrt-v4's built-in masks, scaled to the mean pi/4 over the stop's
// square so they pass the circular stop's light): each mask's transmission matches its
// shape's area, and at the film's centre the mean ray weight equals the mask's exact weight
// integral. (Off the axis pbrt-v4 rotates exit-pupil bounds
// found along +x to the film point's azimuth, which clips the corners of shapes that are
// not rotationally symmetric; that darkening is kept, so it is not tested here.) Through a
// scene, the radially symmetric "gaussian" mask gives the same value at the image centre.
TEST(RealisticCamera, ApertureShapesWeightTheStop) {
    const double rr = 0.005;
    for (const char* shape : {"square", "gaussian", "pentagon", "star"}) {
        auto mask = std::make_shared<ApertureMask>();
        ASSERT_TRUE(ApertureMask::builtin(shape, mask.get()));
        // The shape and its scale, independently: the texels inside are (pi/4) / (the
        // shape's area fraction of the square), the Gaussian's peak (1 - 1/e) / (1 - 2/e)
        // (its mean over the square is (pi/4)(1 - 2/e) before scaling); pixelised polygons
        // within 1%.
        const double pentagon = 2.5 * 0.64 * std::sin(radians(72.0f)), innerStar = std::cos(radians(72.0f)) /
                                                                                      std::cos(radians(36.0f));
        const double star = 5 * innerStar * std::sin(radians(36.0f));
        const double area = std::string(shape) == "square" ? 1.0 : std::string(shape) == "pentagon" ? pentagon : star;
        double peak = 0;
        for (int y = 0; y < mask->height(); ++y)
            for (int x = 0; x < mask->width(); ++x) peak = std::max(peak, double(mask->texel(x, y)));
        const double wantPeak = std::string(shape) == "gaussian" ? (1 - std::exp(-1.0)) / (1 - 2 * std::exp(-1.0))
                                                                  : (kPi / 4) / (area / 4);
        std::printf("%-8s peak transmission %.4f, expected %.4f\n", shape, peak, wantPeak);
        EXPECT_NEAR(peak, wantPeak, 0.01 * wantPeak);
        LensSystem lens = biconvexLens(1.0f, 0.01f, 64, 64, 1 << 14, mask);
        const double want = maskIntegral(*mask, rr, lens.rearZ());
        Rng rng(11);
        const int n = 1 << 20;
        double s = 0, s2 = 0;
        for (int i = 0; i < n; ++i) {
            Ray ray;
            double w = lens.generateRay({32, 32}, {rng.uniform(), rng.uniform()}, &ray);
            s += w;
            s2 += w * w;
        }
        double mean = s / n, sigma = std::sqrt((s2 / n - mean * mean) / (n - 1));
        std::printf("%-8s mean weight %.6f +- %.6f, exact %.6f (%.2f sigma); circular stop %.6f\n", shape, mean, sigma,
                    want, (mean - want) / sigma, kPi * rr * rr / (lens.rearZ() * lens.rearZ() + rr * rr));
        EXPECT_LT(std::fabs(mean - want), 4 * sigma);
    }
    const int res = 16;
    RenderResult r = renderString(realisticScene("\"float aperturediameter\" 10 \"float focusdistance\" 1 "
                                                 "\"string aperture\" \"gaussian\"",
                                                 res, "", "LightSource \"infinite\"\n"),
                                  1024);
    ApertureMask mask;
    ApertureMask::builtin("gaussian", &mask);
    const double want = maskIntegral(mask, rr, biconvexLens(1.0f, 0.01f).rearZ());
    RegionStats c = regionStats(r.image, res / 2 - 2, res / 2 + 2, res / 2 - 2, res / 2 + 2);
    std::printf("scene with \"gaussian\": centre %.6f +- %.6f, exact %.6f (%.2f sigma)\n", c.mean[1], c.stdErr[1], want,
                (c.mean[1] - want) / c.stdErr[1]);
    EXPECT_LT(std::fabs(c.mean[1] - want), 4 * c.stdErr[1]);
}
