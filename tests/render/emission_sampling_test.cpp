// Emission sampling (thesis §10.2: light subpaths start with sampleLe): for every light
// type, sampled origins and directions follow the densities pdfLe reports (chi-square),
// those densities integrate to one (deterministic quadrature over the same cells), pdfLe
// agrees with the densities sampleLe returns, and E[L |cos| / (pdfPos pdfDir)] is the
// light's emitted power, against closed forms (PBRT-CONVENTIONS §3 for "power").
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>

#include "image/image.h"
#include "materials/stats.h"
#include "math/equal_area.h"
#include "math/frame.h"
#include "math/transform.h"
#include "mc/rng.h"
#include "render_helpers.h"
#include "temp_images.h"

using namespace ps;
using namespace ps::test;
namespace fs = std::filesystem;

namespace {

// The lights of a one-line world; a unit sphere at the origin gives lights at infinity a
// known scene disk (bounds [-1,1]^3: radius sqrt(3)).
std::unique_ptr<Scene> lightScene(const std::string& world) {
    setWarningsQuiet(true);
    std::string text = R"(
        LookAt 0 0 5  0 0 0  0 1 0
        Camera "perspective"
        Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
        WorldBegin
        Shape "sphere" "float radius" [ 1 ]
    )" + world;
    return buildScene(parseSceneString(text, ".", "<test>"));
}

// The last light of the scene (the emitter under test is declared after the sphere).
const Light& lastLight(const Scene& s) { return *s.lights().back(); }

// A partition of what sampleLe draws (origins or directions) into cells, with the
// probability pdfLe gives each cell (by quadrature over the cell).
struct Binning {
    std::string what;
    std::function<int(const LightLeSample&)> cellOf;  // -1: in no cell
    std::vector<double> mass;
};

// Directions on a (theta, phi) grid whose pole is `axis`; density(w) is pdfLe's
// directional density of world direction w.
Binning directionGrid(int nTheta, int nPhi, Vec3 axis, const std::function<double(Vec3)>& density) {
    SphereGrid grid(nTheta, nPhi);
    Frame f = Frame::fromNormal(normalize(axis));
    Binning b;
    b.what = "directions";
    b.cellOf = [grid, f](const LightLeSample& s) { return grid.cellOf(f.toLocal(s.ray.d)); };
    b.mass = grid.integrate([&](Vec3 w) { return density(f.toWorld(w)); }, 8);
    return b;
}

// Points on a disk of radius r (centre c, normal n) in nR equal-area rings by nPhi sectors;
// local(p) gives p's offset in the disk's plane as (x, y) and its height off the plane.
struct DiskCells {
    int nR = 8, nPhi = 16;
    int cellOf(float x, float y, float r) const {
        float rr = (x * x + y * y) / (r * r);
        if (!(rr <= 1.0001f)) return -1;
        float phi = std::atan2(y, x);
        if (phi < 0) phi += 2 * kPi;
        int i = std::min(nR - 1, int(rr * nR)), j = std::min(nPhi - 1, int(phi / (2 * kPi) * nPhi));
        return i * nPhi + j;
    }
    // Centre of cell k as (x, y) in units of r, and each cell's area.
    Vec2 centre(int k) const {
        float rr = (k / nPhi + 0.5f) / nR, phi = (k % nPhi + 0.5f) * 2 * kPi / nPhi;
        return {std::sqrt(rr) * std::cos(phi), std::sqrt(rr) * std::sin(phi)};
    }
    double area(float r) const { return M_PI * r * r / (nR * nPhi); }
    int cells() const { return nR * nPhi; }
};

// Origins of rays from lights at infinity: on the disk of the scene's radius r tangent to
// the bounding sphere (centre c) on the light's side, perpendicular to the ray.
Binning infinityDiskCells(const Light& light, Vec3 c, float r, double* maxOffPlane) {
    DiskCells dc;
    Binning b;
    b.what = "disk origins";
    b.cellOf = [=](const LightLeSample& s) {
        Frame f = Frame::fromNormal(-s.ray.d);
        Vec3 q = s.ray.o - (c + (-s.ray.d) * r);
        *maxOffPlane = std::max(*maxOffPlane, double(std::fabs(dot(q, f.n))) / r);
        return dc.cellOf(dot(q, f.s), dot(q, f.t), r);
    };
    for (int k = 0; k < dc.cells(); ++k) {
        float pdfPos, pdfDir;
        light.pdfLe(c, {}, {0, 0, -1}, &pdfPos, &pdfDir);
        b.mass.push_back(pdfPos * dc.area(r));
    }
    return b;
}

struct EmissionStats {
    std::vector<std::vector<double>> counts;  // per binning
    MeanSE power;                             // of L |cos| / (pdfPos pdfDir), green
    int failed = 0;                           // sampleLe gave nothing
    int outside = 0;                          // samples in no cell of some binning
    int pdfMismatches = 0;                    // pdfLe disagreeing with sampleLe's densities
};

// Draws n emitted rays with fixed-seed uniforms; pdfLe is compared with the densities of
// each sample in the components that are not deltas (a delta position has pdfLe 0 and
// sampleLe 1 by convention, likewise a delta direction).
EmissionStats drawEmission(const Light& light, const std::vector<Binning>& bins, int n, uint64_t seed) {
    EmissionStats st;
    st.counts.resize(bins.size());
    for (size_t i = 0; i < bins.size(); ++i) st.counts[i].assign(bins[i].mass.size(), 0.0);
    Rng rng(seed);
    st.power = meanAndError(n, [&] {
        Vec2 uPos(rng.uniform(), rng.uniform()), uDir(rng.uniform(), rng.uniform());
        std::optional<LightLeSample> s = light.sampleLe(uPos, uDir, nullptr);
        if (!s || !(s->pdfPos > 0) || !(s->pdfDir > 0)) {
            ++st.failed;
            return 0.0;
        }
        for (size_t i = 0; i < bins.size(); ++i) {
            int c = bins[i].cellOf(*s);
            if (c < 0 || size_t(c) >= st.counts[i].size()) ++st.outside;
            else st.counts[i][c] += 1;
        }
        float pdfPos, pdfDir;
        light.pdfLe(s->ray.o, s->n, s->ray.d, &pdfPos, &pdfDir);
        auto differs = [](float a, float b) { return !(std::fabs(a - b) <= 1e-3f * b); };
        if ((light.type() != LightType::DeltaDirection && differs(pdfDir, s->pdfDir)) ||
            (light.type() != LightType::DeltaPosition && differs(pdfPos, s->pdfPos)))
            ++st.pdfMismatches;
        double cosine = lengthSquared(s->n) > 0 ? std::fabs(dot(s->n, s->ray.d)) : 1.0;
        return double(s->L.g) * cosine / (double(s->pdfPos) * s->pdfDir);
    });
    return st;
}

// Each binning's masses sum to one (the density integrates to one over its domain) and
// the counts follow them; the power estimate equals `phi` within 4 sigma (plus float
// rounding for estimators with constant weights), and so does light.phi(), or equals
// lightPhi where pbrt-v4's power is an approximation (given when >= 0).
void expectEmission(const char* name, const Light& light, const std::vector<Binning>& bins, double phi,
                    int n = 200000, int maxPdfMismatches = 0, double lightPhi = -1) {
    EmissionStats st = drawEmission(light, bins, n, 11);
    EXPECT_EQ(st.failed, 0) << name;
    EXPECT_EQ(st.outside, 0) << name;
    EXPECT_LE(st.pdfMismatches, maxPdfMismatches) << name;
    for (size_t i = 0; i < bins.size(); ++i) {
        double total = 0;
        std::vector<double> expected;
        for (double m : bins[i].mass) {
            total += m;
            expected.push_back(m * n);
        }
        ChiSquareResult chi = chiSquare(st.counts[i], expected);
        std::printf("%s %s: integral of pdf %.6f, chi2 %.1f (dof %d, p %.3g)\n", name, bins[i].what.c_str(), total,
                    chi.chi2, chi.dof, chi.pValue);
        EXPECT_NEAR(total, 1.0, 1e-3) << name << " " << bins[i].what;
        EXPECT_GT(chi.pValue, 1e-5) << name << " " << bins[i].what;
    }
    std::printf("%s power: %.6g +- %.3g (exact %.6g, phi() %.6g; %d pdf mismatches)\n", name, st.power.mean,
                st.power.se, phi, double(light.phi().g), st.pdfMismatches);
    EXPECT_NEAR(st.power.mean, phi, 4 * st.power.se + 1e-4 * phi) << name;
    if (lightPhi < 0) lightPhi = phi;
    EXPECT_NEAR(light.phi().g, lightPhi, 1e-4 * lightPhi) << name;
}

// Area lights: sampleLi's emission densities for the reverse ray (what BDPT's weights use)
// equal pdfLe's, seen from `ref`.
void expectLiEmissionPdfs(const Light& light, Vec3 ref) {
    Rng rng(5);
    for (int i = 0; i < 100; ++i) {
        auto li = light.sampleLi({ref, {0, 1, 0}}, {rng.uniform(), rng.uniform()});
        ASSERT_TRUE(li.has_value());
        float pdfPos, pdfDir;
        light.pdfLe(li->pLight, li->nLight, -li->wi, &pdfPos, &pdfDir);
        EXPECT_NEAR(li->pdfEmitPos, pdfPos, 1e-4f * pdfPos);
        EXPECT_NEAR(li->pdfEmitDir, pdfDir, 1e-4f * pdfDir);
    }
}

// pdfLe's directional density of an area light (its only dependence is on n . w).
std::function<double(Vec3)> areaDirDensity(const Light& light, Vec3 n) {
    return [&light, n](Vec3 w) {
        float pdfPos, pdfDir;
        light.pdfLe({}, n, w, &pdfPos, &pdfDir);
        return double(pdfDir);
    };
}

// Origins on a flat disk light of radius r about c (normal n), binned in equal areas;
// samples off the disk's plane are in no cell.
Binning diskLightCells(const Light& light, Vec3 c, Vec3 n, float r) {
    DiskCells dc;
    Frame f = Frame::fromNormal(n);
    Binning b;
    b.what = "origins";
    b.cellOf = [=](const LightLeSample& s) {
        Vec3 q = s.ray.o - c;
        if (std::fabs(dot(q, f.n)) > 1e-4f * r) return -1;
        return dc.cellOf(dot(q, f.s), dot(q, f.t), r);
    };
    for (int k = 0; k < dc.cells(); ++k) {
        Vec2 xy = dc.centre(k);
        float pdfPos, pdfDir;
        light.pdfLe(c + f.s * (xy.x * r) + f.t * (xy.y * r), n, n, &pdfPos, &pdfDir);
        b.mass.push_back(pdfPos * dc.area(r));
    }
    return b;
}

}  // namespace

// A point light: directions uniform over the sphere; phi = 4 pi I, and "power" P with
// "rgb I" [2 2 2] emits 2P.
TEST(EmissionSampling, PointLight) {
    auto scene = lightScene(R"(LightSource "point" "rgb I" [ 2 2 2 ] "float power" [ 30 ] "point3 from" [ 0.3 2 0 ])");
    const Light& l = lastLight(*scene);
    Binning dirs = directionGrid(16, 32, {0, 0, 1}, [&](Vec3 w) {
        float pp, pd;
        l.pdfLe({0.3f, 2, 0}, {}, w, &pp, &pd);
        return double(pd);
    });
    expectEmission("point", l, {dirs}, 2 * 30);
}

// A spot light: directions uniform in the cone (grid rows aligned with its edge at 30
// degrees), the smoothstep falloff in the weight; "power" P with "rgb I" [3 3 3] emits 3P.
TEST(EmissionSampling, SpotLight) {
    for (bool power : {false, true}) {
        auto scene = lightScene(std::string(R"(LightSource "spot" "rgb I" [ 3 3 3 ] "point3 from" [ 0 2 0 ] "point3 to" [ 1 0 0.5 ]
                                    "float coneangle" [ 30 ] "float conedeltaangle" [ 10 ] )") +
                                (power ? R"("float power" [ 7 ])" : ""));
        const Light& l = lastLight(*scene);
        Vec3 axis = normalize(Vec3(1, -2, 0.5f));
        Binning dirs = directionGrid(36, 24, axis, [&](Vec3 w) {
            float pp, pd;
            l.pdfLe({0, 2, 0}, {}, w, &pp, &pd);
            return double(pd);
        });
        // The integral of the smoothstep over the cone is half the falloff band.
        double cosS = std::cos(20 * M_PI / 180), cosE = std::cos(30 * M_PI / 180);
        double phi = power ? 3 * 7 : 3 * 2 * M_PI * ((1 - cosS) + (cosS - cosE) / 2);
        expectEmission(power ? "spot (power)" : "spot", l, {dirs}, phi);
    }
}

// A distant light: every ray along -w, origins uniform on the scene disk; phi = L pi r^2.
TEST(EmissionSampling, DistantLight) {
    auto scene = lightScene(R"(LightSource "distant" "rgb L" [ 1.5 1.5 1.5 ] "point3 from" [ 1 2 3 ] "point3 to" [ 0 0 0 ])");
    const Light& l = lastLight(*scene);
    float r = scene->boundsRadius();
    EXPECT_NEAR(r, std::sqrt(3.0f), 1e-3f);
    double offPlane = 0;
    Binning disk = infinityDiskCells(l, scene->boundsCenter(), r, &offPlane);
    Vec3 wLight = normalize(Vec3(1, 2, 3));
    Binning dir;  // the delta direction: one cell
    dir.what = "direction (delta)";
    dir.cellOf = [=](const LightLeSample& s) { return dot(s.ray.d, -wLight) > 1 - 1e-6f ? 0 : -1; };
    dir.mass = {1.0};
    expectEmission("distant", l, {disk, dir}, 1.5 * M_PI * r * r);
    EXPECT_LT(offPlane, 1e-5);
}

// A one-sided disk light (normal -y): cosine-weighted directions on the emitting side,
// origins uniform over the disk; phi = pi L A.
TEST(EmissionSampling, OneSidedDiskLight) {
    auto scene = lightScene(R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 2 2 2 ]
          Translate 0 3 0
          Rotate 90 1 0 0
          Shape "disk" "float radius" [ 0.5 ]
        AttributeEnd)");
    const Light& l = lastLight(*scene);
    Vec3 n(0, -1, 0);
    Binning dirs = directionGrid(16, 32, {0.3f, 0.2f, 1}, areaDirDensity(l, n));
    expectEmission("one-sided disk", l, {diskLightCells(l, {0, 3, 0}, n, 0.5f), dirs}, 2 * M_PI * M_PI * 0.25);
    expectLiEmissionPdfs(l, {0.2f, 0, 0.1f});
}

// Two-sided: both faces emit the same radiance, each side chosen with probability 1/2
// (pdfDir halves), power doubles; with "power" P the light emits 2P for "rgb L" [2 2 2].
TEST(EmissionSampling, TwoSidedDiskLight) {
    for (bool power : {false, true}) {
        auto scene = lightScene(std::string(R"(
            AttributeBegin
              AreaLightSource "diffuse" "rgb L" [ 2 2 2 ] "bool twosided" [ true ] )") +
                                (power ? R"("float power" [ 5 ])" : "") + R"(
              Translate 0 3 0
              Rotate 90 1 0 0
              Shape "disk" "float radius" [ 0.5 ]
            AttributeEnd)");
        const Light& l = lastLight(*scene);
        Vec3 n(0, -1, 0);
        Binning dirs = directionGrid(16, 32, {0.3f, 0.2f, 1}, areaDirDensity(l, n));
        double phi = power ? 2 * 5 : 2 * 2 * M_PI * M_PI * 0.25;
        expectEmission(power ? "two-sided disk (power)" : "two-sided disk", l,
                       {diskLightCells(l, {0, 3, 0}, n, 0.5f), dirs}, phi);
        expectLiEmissionPdfs(l, {0.2f, 0, 0.1f});  // below: the front
        expectLiEmissionPdfs(l, {0.2f, 5, 0.1f});  // above: the back
    }
}

// A spherical emitter: origins uniform over the sphere (equal-area bands in z), directions
// cosine-weighted about each origin's normal (binned in that normal's frame).
TEST(EmissionSampling, SphereLight) {
    auto scene = lightScene(R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 0.5 0.5 0.5 ]
          Translate 0 4 1
          Shape "sphere" "float radius" [ 0.7 ]
        AttributeEnd)");
    const Light& l = lastLight(*scene);
    const Vec3 c(0, 4, 1);
    const int nZ = 12, nPhi = 24;
    const float R = 0.7f;
    Binning origins;
    origins.what = "origins";
    origins.cellOf = [=](const LightLeSample& s) {
        Vec3 q = (s.ray.o - c) / R;
        if (std::fabs(length(q) - 1) > 1e-4f) return -1;
        float phi = std::atan2(q.y, q.x);
        if (phi < 0) phi += 2 * kPi;
        int i = std::clamp(int((q.z + 1) / 2 * nZ), 0, nZ - 1), j = std::min(nPhi - 1, int(phi / (2 * kPi) * nPhi));
        return i * nPhi + j;
    };
    for (int k = 0; k < nZ * nPhi; ++k) {
        float z = -1 + 2 * (k / nPhi + 0.5f) / nZ, phi = (k % nPhi + 0.5f) * 2 * kPi / nPhi;
        Vec3 q(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
        float pdfPos, pdfDir;
        l.pdfLe(c + q * R, q, q, &pdfPos, &pdfDir);
        origins.mass.push_back(pdfPos * 4 * M_PI * R * R / (nZ * nPhi));
    }
    SphereGrid grid(16, 32);
    Binning dirs;
    dirs.what = "directions about n";
    dirs.cellOf = [grid](const LightLeSample& s) { return grid.cellOf(Frame::fromNormal(s.n).toLocal(s.ray.d)); };
    dirs.mass = grid.integrate(areaDirDensity(l, {0, 0, 1}), 8);
    expectEmission("sphere", l, {origins, dirs}, 0.5 * M_PI * 4 * M_PI * R * R);
}

// A triangle of a mesh (each triangle is its own light): origins uniform over it, binned in
// its n^2 congruent sub-triangles; "power" P applies per triangle (PBRT-CONVENTIONS §3).
TEST(EmissionSampling, TriangleLightPower) {
    auto scene = lightScene(R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "float power" [ 4 ]
          Shape "trianglemesh" "point3 P" [ 0 3 0  2 3 0.5  0.5 3.2 1.5 ] "integer indices" [ 0 1 2 ]
        AttributeEnd)");
    const Light& l = lastLight(*scene);
    const Vec3 a(0, 3, 0), e1 = Vec3(2, 3, 0.5f) - a, e2 = Vec3(0.5f, 3.2f, 1.5f) - a;
    Vec3 n = normalize(cross(e1, e2));
    LightLeSample first = *l.sampleLe({0.3f, 0.3f}, {0.3f, 0.3f}, nullptr);
    n = dot(n, first.n) < 0 ? -n : n;
    const int m = 8;
    const double area = 0.5 * length(cross(e1, e2));
    double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2), det = g11 * g22 - g12 * g12;
    // Sub-triangle (i, j) lower/upper as one index; those outside the triangle get no mass.
    Binning origins;
    origins.what = "origins";
    origins.cellOf = [=](const LightLeSample& s) {
        Vec3 q = s.ray.o - a;
        if (std::fabs(dot(q, n)) > 1e-5f) return -1;
        double r1 = dot(q, e1), r2 = dot(q, e2);
        double b1 = (g22 * r1 - g12 * r2) / det * m, b2 = (g11 * r2 - g12 * r1) / det * m;
        int i = std::clamp(int(b1), 0, m - 1), j = std::clamp(int(b2), 0, m - 1);
        int upper = (b1 - i) + (b2 - j) >= 1;
        if (i + j + upper > m - 1) return -1;
        return (i * m + j) * 2 + upper;
    };
    origins.mass.assign(size_t(2 * m * m), 0.0);
    for (int i = 0; i < m; ++i)
        for (int j = 0; i + j < m; ++j)
            for (int upper = 0; upper < 2 && i + j + upper < m; ++upper) {
                float b1 = (i + (upper ? 2 : 1) / 3.0f) / m, b2 = (j + (upper ? 2 : 1) / 3.0f) / m;
                float pdfPos, pdfDir;
                l.pdfLe(a + e1 * b1 + e2 * b2, n, n, &pdfPos, &pdfDir);
                origins.mass[(i * m + j) * 2 + upper] = pdfPos * area / (m * m);
            }
    // Cells outside the triangle: none observed (drawEmission counts samples in no cell).
    std::vector<double> mass;
    for (double v : origins.mass)
        if (v > 0) mass.push_back(v);
    std::vector<int> compact(origins.mass.size(), -1);
    for (size_t k = 0, c = 0; k < origins.mass.size(); ++k)
        if (origins.mass[k] > 0) compact[k] = int(c++);
    auto raw = origins.cellOf;
    origins.cellOf = [raw, compact](const LightLeSample& s) {
        int k = raw(s);
        return k < 0 ? -1 : compact[k];
    };
    origins.mass = mass;
    Binning dirs = directionGrid(16, 32, n, areaDirDensity(l, n));
    expectEmission("triangle (power)", l, {origins, dirs}, 4.0);
    expectLiEmissionPdfs(l, a + n * 2 + e1 * 0.2f);
}

// The uniform sky: directions uniform, origins on the scene disk; phi = 4 pi L pi r^2.
TEST(EmissionSampling, UniformInfiniteLight) {
    auto scene = lightScene(R"(LightSource "infinite" "rgb L" [ 0.7 0.7 0.7 ])");
    const Light& l = lastLight(*scene);
    float r = scene->boundsRadius();
    double offPlane = 0;
    Binning disk = infinityDiskCells(l, scene->boundsCenter(), r, &offPlane);
    Binning dirs = directionGrid(16, 32, {0, 0, 1}, [&](Vec3 w) {
        float pp, pd;
        l.pdfLe({}, {}, w, &pp, &pd);
        return double(pd);
    });
    expectEmission("uniform infinite", l, {disk, dirs}, 0.7 * 4 * M_PI * M_PI * r * r);
    EXPECT_LT(offPlane, 1e-5);
}

// An environment map with a 3-decade spread of texel values (a hot spot over a dim
// gradient), rotated: directions binned by texel, where pdfLe is constant, so the cell
// probabilities are exact (equal-area texels subtend 4 pi / N; latitude-longitude ones
// (2 pi / w)(cos theta0 - cos theta1)); phi = integral of L over the sphere times pi r^2.
TEST(EmissionSampling, ImageInfiniteLight) {
    fs::path dir = fs::temp_directory_path() / ("pathspace-emit-" + std::to_string(getpid()));
    fs::create_directories(dir);
    const Transform rot = Transform::rotate(-70, {1, 0.5f, 0});
    for (bool equalArea : {true, false}) {
        const int w = equalArea ? 16 : 32, h = 16;
        Image img(w, h);
        Rng rng(9);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                bool hot = x >= 3 && x < 6 && y >= 9 && y < 12;
                float v = hot ? 200.0f : 0.05f + 0.5f * (x + y) / (w + h) + 0.2f * rng.uniform();
                img.set(x, y, Spectrum(v));
            }
        std::string file = (dir / (equalArea ? "ea.pfm" : "ll.pfm")).string();
        writeImage(file, img);
        auto scene = lightScene(R"(
            AttributeBegin
              Rotate -70 1 0.5 0
              LightSource "infinite" "string filename" [ ")" + file + R"(" ] "float scale" [ 0.5 ]
            AttributeEnd)");
        const Light& l = lastLight(*scene);
        float r = scene->boundsRadius();
        double offPlane = 0;
        Binning disk = infinityDiskCells(l, scene->boundsCenter(), r, &offPlane);
        // The texel a ray's direction comes from (the light sits along -d, in light space).
        const Transform lightFromWorld = rot.inverse();
        auto uvOf = [=](Vec3 wLight) {
            if (equalArea) return equalAreaSphereToSquare(wLight);
            float phi = std::atan2(wLight.y, wLight.x);
            if (phi < 0) phi += 2 * kPi;
            return Vec2(phi / (2 * kPi), std::acos(std::clamp(wLight.z, -1.0f, 1.0f)) / kPi);
        };
        Binning texels;
        texels.what = "texels";
        texels.cellOf = [=](const LightLeSample& s) {
            Vec2 uv = uvOf(normalize(lightFromWorld.vector(-s.ray.d)));
            return std::clamp(int(uv.y * h), 0, h - 1) * w + std::clamp(int(uv.x * w), 0, w - 1);
        };
        double exact = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                Vec2 uv((x + 0.5f) / w, (y + 0.5f) / h);
                double theta = M_PI * uv.y;
                Vec3 wl = equalArea ? equalAreaSquareToSphere(uv)
                                    : Vec3(float(std::sin(theta) * std::cos(2 * M_PI * uv.x)),
                                           float(std::sin(theta) * std::sin(2 * M_PI * uv.x)), float(std::cos(theta)));
                double omega = equalArea ? 4 * M_PI / (w * h)
                                         : (2 * M_PI / w) * (std::cos(M_PI * y / h) - std::cos(M_PI * (y + 1) / h));
                float pdfPos, pdfDir;
                l.pdfLe({}, {}, -normalize(rot.vector(wl)), &pdfPos, &pdfDir);
                // Latitude-longitude densities vary as 1/sin(theta) inside a texel, with a
                // constant density in (u, v): its mass is pdf(centre) sin(theta_c) times the
                // texel's (u, v) area mapped to solid angle at the centre.
                texels.mass.push_back(equalArea ? pdfDir * omega
                                                : pdfDir * std::sin(theta) * 2 * M_PI * M_PI / (w * h));
                exact += 0.5 * img.get(x, y).g * omega;
            }
        const char* name = equalArea ? "image infinite (equal-area)" : "image infinite (lat-long)";
        expectEmission(name, l, {disk, texels}, exact * M_PI * r * r, 200000, 200000 / 1000);
        EXPECT_LT(offPlane, 1e-5);
    }
    fs::remove_all(dir);
}

namespace {

// A 16 x 16 map: a hot patch 3 decades above a dim gradient.
Image hotSpotImage(int w, int h) {
    Image img(w, h);
    Rng rng(9);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool hot = x >= 3 && x < 6 && y >= 9 && y < 12;
            float v = hot ? 200.0f : 0.05f + 0.5f * (x + y) / (w + h) + 0.2f * rng.uniform();
            img.set(x, y, Spectrum(v, 0.5f * v + 0.1f, 0.2f));
        }
    return img;
}

}  // namespace

// A goniometric light (rotated; its frame swaps y and z): directions binned by texel,
// where pdfLe is constant, so each cell's probability is pdfLe times 4 pi / N exactly;
// phi = 4 pi I times the mean texel (the mean of R, G, B), or with "power" P, P times the
// RGB factor of I and times "scale".
TEST(EmissionSampling, GoniometricLight) {
    TempImages tmp("emit-gonio");
    const int res = 16;
    Image img = hotSpotImage(res, res);
    std::string file = tmp.write("gonio.pfm", img);
    const Transform lightFromWorld = Transform::rotate(-70, {1, 0.5f, 0}).inverse();
    auto swapYZ = [](Vec3 v) { return Vec3(v.x, v.z, v.y); };
    for (bool power : {false, true}) {
        auto scene = lightScene(R"(
            AttributeBegin
              Translate 0 3 0
              Rotate -70 1 0.5 0
              LightSource "goniometric" "rgb I" [ 1 2 3 ] "float scale" [ 0.5 ] "string filename" [ ")" + file +
                                "\" ]" + (power ? R"( "float power" [ 7 ])" : "") + R"(
            AttributeEnd)");
        const Light& l = lastLight(*scene);
        Binning texels;
        texels.what = "texels";
        texels.cellOf = [=](const LightLeSample& s) {
            Vec2 uv = equalAreaSphereToSquare(normalize(swapYZ(lightFromWorld.vector(s.ray.d))));
            return std::clamp(int(uv.y * res), 0, res - 1) * res + std::clamp(int(uv.x * res), 0, res - 1);
        };
        double meanY = 0;
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) {
                Vec3 wl = equalAreaSquareToSphere({(x + 0.5f) / res, (y + 0.5f) / res});
                float pdfPos, pdfDir;
                l.pdfLe({0, 3, 0}, {}, normalize(lightFromWorld.inverse().vector(swapYZ(wl))), &pdfPos, &pdfDir);
                texels.mass.push_back(pdfDir * 4 * M_PI / (res * res));
                Spectrum c = img.get(x, y);
                meanY += (c.r + c.g + c.b) / 3 / (res * res);
            }
        double phi = power ? 0.5 * 2 * 7 : 0.5 * 2 * 4 * M_PI * meanY;  // "scale" multiplies "power"
        expectEmission(power ? "goniometric (power)" : "goniometric", l, {texels}, phi, 200000, 200000 / 1000);
    }
}

// A goniometric light under a transform that scales unevenly: a constant map emits I in
// every world direction, while the light-space directions it samples bunch up; pdfLe (with
// the Jacobian of the direction mapping) still integrates to one over world directions and
// matches where samples land.
TEST(EmissionSampling, GoniometricLightUnderNonUniformScale) {
    TempImages tmp("emit-gonio-scale");
    Image img(8, 8);
    for (float& v : img.rgb) v = 0.6f;
    std::string file = tmp.write("flat.pfm", img);
    auto scene = lightScene(R"(
        AttributeBegin
          Translate 0 3 0
          Scale 1 3 0.4
          LightSource "goniometric" "string filename" [ ")" + file + R"(" ]
        AttributeEnd)");
    const Light& l = lastLight(*scene);
    Binning dirs = directionGrid(16, 32, {0.2f, 1, 0.1f}, [&](Vec3 w) {
        float pp, pd;
        l.pdfLe({0, 3, 0}, {}, w, &pp, &pd);
        return double(pd);
    });
    expectEmission("goniometric (scaled)", l, {dirs}, 0.6 * 4 * M_PI);
}

// A projection light (rotated; 6 x 4 texels, fov 50): directions binned by texel. Over a
// texel pdfLe d omega = pdfUV dA / A on the plane z = 1 (constant), so quadrature on the
// screen is exact. The true power sums texel values times their exact solid angles
// (rectangles on the plane z = 1: corner function atan(xy / sqrt(1 + x^2 + y^2))), while
// pbrt-v4's phi (and "power") use each texel's solid angle at its centre, cos^3 dA.
TEST(EmissionSampling, ProjectionLight) {
    TempImages tmp("emit-projection");
    const int w = 6, h = 4;
    Image img = hotSpotImage(w, h);
    img.set(4, 1, Spectrum(80, 40, 20));
    std::string file = tmp.write("slide.pfm", img);
    const Transform lightFromWorld = (Transform::rotate(30, {1, 2, 0.5f}) * Transform::scale({1, -1, 1})).inverse();
    const double t = std::tan(25 * M_PI / 180), a = double(w) / h;  // screen [-a, a] x [-1, 1]
    auto corner = [](double x, double y) { return std::atan(x * y / std::sqrt(1 + x * x + y * y)); };
    for (bool power : {false, true}) {
        auto scene = lightScene(R"(
            AttributeBegin
              Translate 0 3 0
              Rotate 30 1 2 0.5
              LightSource "projection" "float fov" [ 50 ] "float scale" [ 0.5 ] "string filename" [ ")" + file +
                                "\" ]" + (power ? R"( "float power" [ 7 ])" : "") + R"(
            AttributeEnd)");
        const Light& l = lastLight(*scene);
        Binning texels;
        texels.what = "texels";
        texels.cellOf = [=](const LightLeSample& s) {
            Vec3 wl = lightFromWorld.vector(s.ray.d);
            if (!(wl.z > 0)) return -1;
            double sx = wl.x / (wl.z * t), sy = wl.y / (wl.z * t);
            int x = int(std::floor((sx + a) / (2 * a) * w)), y = int(std::floor((sy + 1) / 2 * h));
            return x < 0 || x >= w || y < 0 || y >= h ? -1 : y * w + x;
        };
        const int sub = 8;
        double exactG = 0, midpointG = 0, midpointLum = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double sx0 = -a + 2 * a * x / w, sy0 = -1 + 2.0 * y / h, dsx = 2 * a / w, dsy = 2.0 / h;
                double mass = 0;
                for (int i = 0; i < sub; ++i)
                    for (int j = 0; j < sub; ++j) {
                        double px = (sx0 + (i + 0.5) * dsx / sub) * t, py = (sy0 + (j + 0.5) * dsy / sub) * t;
                        double c = 1 / std::sqrt(1 + px * px + py * py);
                        Vec3 wl(float(px * c), float(py * c), float(c));
                        float pdfPos, pdfDir;
                        l.pdfLe({0, 3, 0}, {}, normalize(lightFromWorld.inverse().vector(wl)), &pdfPos, &pdfDir);
                        mass += pdfDir * c * c * c * (dsx * t / sub) * (dsy * t / sub);
                    }
                texels.mass.push_back(mass);
                double x0 = sx0 * t, x1 = (sx0 + dsx) * t, y0 = sy0 * t, y1 = (sy0 + dsy) * t;
                double omega = corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
                double xc = (x0 + x1) / 2, yc = (y0 + y1) / 2;
                double cos3 = std::pow(1 + xc * xc + yc * yc, -1.5), dA = (x1 - x0) * (y1 - y0);
                exactG += img.get(x, y).g * omega;
                midpointG += img.get(x, y).g * cos3 * dA;
                midpointLum += img.get(x, y).luminance() * cos3 * dA;
            }
        double scale = power ? 0.5 * 7 / midpointLum : 0.5;
        std::printf("projection: exact power / pbrt-v4's midpoint power = %.6f\n", exactG / midpointG);
        expectEmission(power ? "projection (power)" : "projection", l, {texels}, scale * exactG, 200000, 200000 / 1000,
                       scale * midpointG);
    }
}

// An area light with an emission image, one triangle with its own uv: directions cosine-
// weighted as without an image, and the power is pi times the integral of the radiance
// over the triangle, scale times the image bilinearly interpolated at (u, 1 - v) (computed
// here by the centroid rule on 128^2 sub-triangles, exact where the interpolation is
// linear). pbrt-v4's phi uses the image's mean instead, and "power" P divides by pi, the
// area and the mean luminance.
TEST(EmissionSampling, ImageAreaLight) {
    TempImages tmp("emit-area-image");
    const int w = 16, h = 16;
    Image img = hotSpotImage(w, h);
    std::string file = tmp.write("emit.pfm", img);
    auto bilerp = [&](double s, double tt) {
        double x = s * w - 0.5, y = (1 - tt) * h - 0.5;
        int x0 = int(std::floor(x)), y0 = int(std::floor(y));
        double fx = x - x0, fy = y - y0;
        auto at = [&](int i, int j) { return double(img.get(std::clamp(i, 0, w - 1), std::clamp(j, 0, h - 1)).g); };
        return (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) + (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
    };
    const Vec3 a(0, 3, 0), b(2, 3, 0.5f), c(0.5f, 3.2f, 1.5f);
    const Vec2 ta(0.1f, 0.2f), tb(0.9f, 0.3f), tc(0.4f, 0.95f);
    const double area = 0.5 * length(cross(b - a, c - a));
    const int m = 128;
    double integral = 0;  // of the interpolated green channel over the triangle, per unit area
    for (int i = 0; i < m; ++i)
        for (int j = 0; i + j < m; ++j)
            for (int upper = 0; upper < 2 && i + j + upper < m; ++upper) {
                double b1 = (i + (upper ? 2 : 1) / 3.0) / m, b2 = (j + (upper ? 2 : 1) / 3.0) / m;
                Vec2 uv = ta + (tb - ta) * float(b1) + (tc - ta) * float(b2);
                integral += bilerp(uv.x, uv.y) / (m * m);
            }
    double meanG = 0, meanLum = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            meanG += img.get(x, y).g / (w * h);
            meanLum += img.get(x, y).luminance() / (w * h);
        }
    for (bool power : {false, true}) {
        auto scene = lightScene(R"(
            AttributeBegin
              AreaLightSource "diffuse" "float scale" [ 0.5 ] "string filename" [ ")" + file + "\" ]" +
                                (power ? R"( "float power" [ 4 ])" : "") + R"(
              Shape "trianglemesh" "point3 P" [ 0 3 0  2 3 0.5  0.5 3.2 1.5 ] "integer indices" [ 0 1 2 ]
                  "point2 uv" [ 0.1 0.2  0.9 0.3  0.4 0.95 ]
            AttributeEnd)");
        const Light& l = lastLight(*scene);
        Vec3 n = normalize(cross(b - a, c - a));
        Binning dirs = directionGrid(16, 32, n, areaDirDensity(l, n));
        double scale = power ? 0.5 * 4 / (M_PI * area * meanLum) : 0.5;
        expectEmission(power ? "image area light (power)" : "image area light", l, {dirs},
                       M_PI * scale * integral * area, 200000, 0, M_PI * scale * meanG * area);
        expectLiEmissionPdfs(l, a + n * 2 + (b - a) * 0.2f);
    }
}
