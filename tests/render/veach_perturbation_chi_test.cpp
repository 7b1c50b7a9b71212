// Chi-square checks of Veach's perturbations (thesis §11.4.3) against a model of the scene
// that shares no code with them: flat rectangles (diffuse or mirror) traced in double
// precision by the test itself, and a pinhole built from the LookAt.
//  - The histogram of the free vertex a perturbation proposes (a diffuse point, over a window
//    of a diffuse rectangle) must match the counts obtained by drawing the documented offset
//    (film offset of density proportional to 1 / r on [r1, r2], r2 covering 5% of the image;
//    angle of density proportional to 1 / theta on [theta1, theta2]; uniform azimuth) with the
//    test's own random numbers and tracing the model: Pearson's chi-square p > 1e-4 and the
//    binned total within 4 sigma. A radius or angle density a few percent off fails here.
//  - The ratio T(y -> x) / T(x -> y) the perturbation reports must equal the independent one:
//    T in the area measure of the moved diffuse vertices is the offset's density (symmetric,
//    it cancels) times Jacobians from the film or the direction to those vertices, taken by
//    finite differences of the model; T itself lives in the pseudo-measure that f shares
//    (path_space.h: a specular vertex counts with a unit delta), which differs from the area
//    measure, across a flat mirror M between vertices A and B, by the factor
//    c = |cos at M| (|AM| + |MB|)^2 / (|AM|^2 |MB|^2) (the mirror's image of B lies at
//    |AM| + |MB| from A, while the pseudo-measure takes the two edges' geometry apart); f
//    carries the same factor, so the acceptance is the same in either measure.
// Scenes: a diffuse point seen in a mirror (lens perturbation, L D S E), a caustic from a
// mirror seen directly (caustic perturbation, L S D E) and a diffuse point reached by a camera
// ray and then through a mirror (multi-chain perturbation, L D S D E).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "../materials/stats.h"
#include "render_helpers.h"
#include "transport/mlt/veach/veach_mlt.h"

using namespace ps;
using namespace ps::test;

namespace {

struct D3 {
    double x = 0, y = 0, z = 0;
};
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(double s, D3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(D3 a) { return std::sqrt(dot(a, a)); }
D3 unit(D3 a) { return (1 / norm(a)) * a; }
D3 of(Vec3 v) { return {v.x, v.y, v.z}; }

constexpr int kRes = 64;
constexpr double kFov = 40;
constexpr int kBins = 12;

// A rectangle p0 + u a + v b, u, v in [0, 1], with a perpendicular to b.
struct Rect {
    D3 p0, a, b;
    bool mirror;
    D3 normal() const { return unit(cross(a, b)); }
    // The ray's parameter at the hit, or nothing.
    std::optional<double> hit(D3 o, D3 d) const {
        const D3 n = normal();
        const double dn = dot(d, n);
        if (std::fabs(dn) < 1e-12) return {};
        const double t = dot(p0 - o, n) / dn;
        if (!(t > 1e-5)) return {};  // not the surface a ray leaves (float vertices)
        const D3 q = o + t * d - p0;
        const double u = dot(q, a) / dot(a, a), v = dot(q, b) / dot(b, b);
        if (u < 0 || u > 1 || v < 0 || v > 1) return {};
        return t;
    }
};

// The scene: rectangles, a point light (or a distant light whose light travels along
// `distant`) and the pinhole at the origin looking along +z.
struct Model {
    std::vector<Rect> rects;
    D3 light;
    std::optional<D3> distant;

    std::string text() const {
        std::ostringstream s;
        s << "LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\" \"float fov\" [ " << kFov
          << " ]\nFilm \"rgb\" \"integer xresolution\" [ " << kRes << " ] \"integer yresolution\" [ " << kRes
          << " ]\nPixelFilter \"box\"\nWorldBegin\n";
        if (distant)
            s << "LightSource \"distant\" \"rgb L\" [ 1 1 1 ] \"point3 from\" [ 0 0 0 ] \"point3 to\" [ " << distant->x << " "
              << distant->y << " " << distant->z << " ]\n";
        else
            s << "LightSource \"point\" \"rgb I\" [ 1 1 1 ] \"point3 from\" [ " << light.x << " " << light.y << " "
              << light.z << " ]\n";
        for (const Rect& r : rects) {
            s << (r.mirror ? "Material \"conductor\" \"rgb reflectance\" [ 0.9 0.9 0.9 ] \"float roughness\" [ 0 ]\n"
                           : "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n");
            const D3 p[4] = {r.p0, r.p0 + r.a, r.p0 + r.b, r.p0 + r.a + r.b};
            s << "Shape \"bilinearmesh\" \"point3 P\" [";
            for (const D3& q : p) s << " " << q.x << " " << q.y << " " << q.z;
            s << " ]\n";
        }
        return s.str();
    }

    // The nearest rectangle the ray meets before tMax, and where.
    int nearest(D3 o, D3 d, double tMax, D3* p) const {
        int best = -1;
        for (size_t i = 0; i < rects.size(); ++i)
            if (auto t = rects[i].hit(o, d); t && *t < tMax) tMax = *t, best = int(i);
        if (best >= 0) *p = o + tMax * d;
        return best;
    }
    bool visible(D3 a, D3 b) const {
        D3 p;
        const double d = norm(b - a);
        return nearest(a, (1 / d) * (b - a), d * (1 - 1e-7), &p) < 0;
    }
    // From o along d through `mirrors` mirror reflections to a diffuse point: the points met
    // (mirrors then the diffuse one), or nothing if the ray escapes or meets another sequence.
    std::optional<std::vector<D3>> chain(D3 o, D3 d, int mirrors) const {
        std::vector<D3> pts;
        for (int i = 0; i <= mirrors; ++i) {
            D3 p;
            const int r = nearest(o, d, 1e30, &p);
            if (r < 0 || rects[size_t(r)].mirror != (i < mirrors)) return {};
            pts.push_back(p);
            const D3 n = rects[size_t(r)].normal();
            d = d - 2 * dot(d, n) * n;
            o = p;
        }
        return pts;
    }
};

// The pinhole: raster (px, py), y down, onto the camera's +x right, +y up, +z forward.
const double kScale = 2 * std::tan(kFov / 2 * kPi / 180) / kRes;
D3 filmRay(double px, double py) { return unit({(px - kRes / 2.0) * kScale, (kRes / 2.0 - py) * kScale, 1}); }
void filmOf(D3 d, double* px, double* py) {
    *px = kRes / 2.0 + d.x / d.z / kScale;
    *py = kRes / 2.0 - d.y / d.z / kScale;
}

// The pseudo-measure's factor across flat mirror M between A and B (see the top).
double mirrorFactor(D3 a, D3 m, D3 b, D3 nM) {
    const double da = norm(m - a), db = norm(b - m);
    return std::fabs(dot(nM, (1 / da) * (m - a))) * (da + db) * (da + db) / (da * da * db * db);
}

// |d(offset) / dA| at the end of map(0, 0), map being a point as a function of a 2D offset,
// by central differences.
template <class Map>
double jacobian(const Map& map, double h) {
    const D3 pu = (1 / (2 * h)) * (map(h, 0) - map(-h, 0)), pv = (1 / (2 * h)) * (map(0, h) - map(0, -h));
    return 1 / norm(cross(pu, pv));
}

// Film to the diffuse point reached through `mirrors` mirrors (per pixel^2 per unit area).
double filmJacobian(const Model& m, D3 lensToFirst, int mirrors) {
    double px, py;
    filmOf(lensToFirst, &px, &py);
    return jacobian([&](double u, double v) { return m.chain({}, filmRay(px + u, py + v), mirrors)->back(); }, 1e-4);
}

// Solid angle at q around w to the diffuse point reached through `mirrors` mirrors.
double angleJacobian(const Model& m, D3 q, D3 w, int mirrors) {
    const D3 t = unit(std::fabs(w.x) < 0.9 ? cross(w, {1, 0, 0}) : cross(w, {0, 1, 0})), s = cross(w, t);
    return jacobian([&](double a, double b) { return m.chain(q, unit(w + a * t + b * s), mirrors)->back(); }, 1e-7);
}

// The documented offsets, drawn with the test's own numbers.
struct Offsets {
    double r1 = 0.1, r2 = std::sqrt(0.05 * kRes * kRes / kPi), theta1 = 1e-4, theta2 = 0.1;
    void film(Rng& rng, double px, double py, double* qx, double* qy) const {
        const double r = r1 * std::pow(r2 / r1, rng.uniformDouble()), phi = 2 * kPi * rng.uniformDouble();
        *qx = px + r * std::cos(phi);
        *qy = py + r * std::sin(phi);
    }
    D3 direction(Rng& rng, D3 w) const {
        const double theta = theta1 * std::pow(theta2 / theta1, rng.uniformDouble()), phi = 2 * kPi * rng.uniformDouble();
        const D3 t = unit(std::fabs(w.x) < 0.9 ? cross(w, {1, 0, 0}) : cross(w, {0, 1, 0})), s = cross(w, t);
        return unit(std::cos(theta) * w + std::sin(theta) * (std::cos(phi) * t + std::sin(phi) * s));
    }
};

// A square window of half-size `half` on rectangle `rect` around the old point c, in kBins^2
// bins; c lies in the middle of a bin, not on a corner where float rounding would share the
// offsets' peak (a third of the angles are below 1e-3) between four bins at random.
struct Window {
    const Rect* rect;
    D3 c;
    double half;
    int bin(D3 p) const {
        const D3 ua = unit(rect->a), vb = unit(rect->b);
        if (std::fabs(dot(p - rect->p0, rect->normal())) > 1e-4) return -1;
        const double shift = 0.5 / kBins;
        const double u = (dot(p - c, ua) + half) / (2 * half) + shift, v = (dot(p - c, vb) + half) / (2 * half) + shift;
        if (!(u >= 0 && u < 1 && v >= 0 && v < 1)) return -1;
        return std::min(kBins - 1, int(u * kBins)) * kBins + std::min(kBins - 1, int(v * kBins));
    }
};

struct Perturbed {
    Model model;
    std::unique_ptr<Scene> scene;
    std::unique_ptr<VeachMLTIntegrator> integrator;
    ScratchBuffer arena;
    MltPath x;
    Vec2 rasterX;

    explicit Perturbed(const Model& m) : model(m) {
        setWarningsQuiet(true);
        scene = buildScene(parseSceneString(model.text(), ".", "<test>"));
        integrator = std::make_unique<VeachMLTIntegrator>(*scene, 5, MetropolisParams{});
    }
    const PathSpace& space() const { return integrator->space(); }
    MltVertex light() {
        PathStats stats;
        Rng rng(1);
        std::vector<MltVertex> l;
        EXPECT_TRUE(space().walk(l, 1, TransportMode::Importance, 0.0f, {}, rng, arena, stats));
        return l.at(0);
    }
    MltVertex lens(Ray* ray) {
        MltVertex v;
        *ray = space().cameraRay(Vec2(kRes / 2.0f, kRes / 2.0f), Vec2(0.5f, 0.5f), 0.0f, {}, &v);
        return v;
    }
    MltVertex trace(const Ray& ray, bool specular) {
        PathStats stats;
        MltVertex v;
        EXPECT_TRUE(space().trace(ray, {}, arena, stats, v));
        if (specular) {
            EXPECT_TRUE(v.takeSpecularRole());
        }
        return v;
    }
    void finish() {
        EXPECT_GT(space().contribution(x, &rasterX).luminance(), 0.0f);
        // The model's pinhole sees the lens's first vertex where the renderer's film does.
        double px, py;
        filmOf(of(x[x.size() - 2].p) - of(x.back().p), &px, &py);
        EXPECT_NEAR(px, rasterX.x, 1e-3);
        EXPECT_NEAR(py, rasterX.y, 1e-3);
    }
};

// Observed proposals against the model's own draws, and the reported ratios against the
// model's. `propose` runs the perturbation; `draw` makes one of the model's proposals (the
// binned point, or nothing); `modelRatio` is T(y -> x) / T(x -> y) from the model.
template <class Propose, class Draw, class ModelRatio>
void check(const char* what, const Window& window, int proposals, const Propose& propose, const Draw& draw,
           const ModelRatio& modelRatio, int binnedVertex) {
    std::vector<double> observed(kBins * kBins, 0), drawn(kBins * kBins, 0);
    ScratchBuffer arena;
    PathStats stats;
    Rng rng(23);
    MltPath y;
    int ratioChecks = 0, ratiosOff = 0;
    double worst = 0;
    for (int n = 0; n < proposals; ++n) {
        double ratio = 0;
        if (!propose(rng, arena, stats, y, &ratio)) continue;
        const int b = window.bin(of(y[size_t(binnedVertex)].p));
        if (b >= 0) observed[size_t(b)] += 1;
        if (n % 64 == 0) {
            const double expected = modelRatio(y);
            const double off = std::fabs(ratio / expected - 1);
            worst = std::max(worst, off);
            ++ratioChecks;
            if (!(off < 2e-3)) ++ratiosOff;
        }
    }
    const int draws = 4 * proposals;
    Rng own(29);
    for (int n = 0; n < draws; ++n)
        if (std::optional<D3> p = draw(own)) {
            const int b = window.bin(*p);
            if (b >= 0) drawn[size_t(b)] += 1;
        }
    const double scale = double(proposals) / draws;
    std::vector<double> e(drawn.size()), v(drawn.size());
    double o = 0, et = 0, vt = 0;
    for (size_t k = 0; k < drawn.size(); ++k) {
        e[k] = drawn[k] * scale, v[k] = drawn[k] * scale * scale;
        o += observed[k], et += e[k], vt += v[k];
    }
    const ChiSquareResult r = chiSquare(observed, e, v);
    if (std::getenv("PS_DEBUG_BINS"))  // each bin's (O - E) / sigma
        for (size_t k = 0; k < e.size(); ++k)
            std::printf("%+6.1f%s", (observed[k] - e[k]) / std::sqrt(e[k] + v[k] + 1e-9), (k + 1) % kBins ? " " : "\n");
    const double z = (o - et) / std::sqrt(et + vt);
    std::printf("[ %s ] %.0f proposals binned, %.1f expected (%.2f sigma); chi2 %.1f on %d dof, p = %.3g; "
                "%d ratios checked, worst relative error %.2g\n",
                what, o, et, z, r.chi2, r.dof, r.pValue, ratioChecks, worst);
    EXPECT_GT(r.pValue, 1e-4) << what;
    EXPECT_LT(std::fabs(z), 4.0) << what;
    EXPECT_GT(o, 0.5 * proposals) << what << ": too few proposals land in the window";
    EXPECT_LT(o, 0.97 * proposals) << what << ": the window must cut the tails for the total to say something";
    EXPECT_GT(ratioChecks, 1000) << what;
    EXPECT_EQ(ratiosOff, 0) << what << ": worst relative error " << worst;
}

// A mirror at 45 degrees in front of the camera (z + y = 3) folds its view down to a floor
// (y = -2), lit by a point light in front of the mirror.
Model mirrorToFloor() {
    Model m;
    m.rects = {{{-1.5, -1.2, 4.2}, {3, 0, 0}, {0, 2.4, -2.4}, true}, {{-2, -2, 0.5}, {4, 0, 0}, {0, 0, 5}, false}};
    m.light = {0, -1.5, 1.5};
    return m;
}

// A wall (z = 3) in front of the camera, a mirror floor (y = -1, z in [0.5, 2.5]) and a
// diffuse ceiling over the camera (y = 1).
Model wallMirrorCeiling(D3 light) {
    Model m;
    m.rects = {{{-3, -3, 3}, {6, 0, 0}, {0, 6, 0}, false},
               {{-2, -1, 0.5}, {4, 0, 0}, {0, 0, 2}, true},
               {{-2, 1, -1.5}, {4, 0, 0}, {0, 0, 3}, false}};
    m.light = light;
    return m;
}

}  // namespace

// Lens perturbation, L D S E: the film point moves, the camera ray reflects in the mirror to a
// new floor point, joined to the light.
TEST(VeachPerturbationChiSquare, LensThroughAMirror) {
    Perturbed s(mirrorToFloor());
    Ray ray;
    const MltVertex lens = s.lens(&ray);
    const MltVertex mirror = s.trace(ray, true);
    Ray next;
    ASSERT_TRUE(s.space().followSpecular(mirror, ray, true, TransportMode::Radiance, next));
    const MltVertex floor = s.trace(next, false);
    s.x = {s.light(), floor, mirror, lens};
    s.finish();
    const Perturbations& p = s.integrator->perturbations();
    ASSERT_TRUE(p.lensApplies(s.x));
    const Model& m = s.model;
    const Offsets offsets;
    EXPECT_NEAR(p.r2(), offsets.r2, 1e-9);
    // T's Jacobian part at path z, in the pseudo-measure.
    auto t = [&](const MltPath& z) {
        const D3 e = of(z[3].p), mp = of(z[2].p), d = of(z[1].p);
        return filmJacobian(m, mp - e, 1) * mirrorFactor(e, mp, d, m.rects[0].normal());
    };
    const double tx = t(s.x);
    const Window window{&m.rects[1], of(floor.p), 0.3};
    check(
        "lens perturbation, floor seen in a mirror", window, 1000000,
        [&](Rng& rng, ScratchBuffer& a, PathStats& st, MltPath& y, double* ratio) {
            return p.lens(s.x, s.rasterX, rng, a, st, y, ratio);
        },
        [&](Rng& rng) -> std::optional<D3> {
            double qx, qy;
            offsets.film(rng, s.rasterX.x, s.rasterX.y, &qx, &qy);
            auto c = m.chain({}, filmRay(qx, qy), 1);
            if (!c || !m.visible(c->back(), m.light)) return {};
            return c->back();
        },
        [&](const MltPath& y) { return tx / t(y); }, 1);
}

// Caustic perturbation, L S D E: the direction leaving the point light moves, reflects in the
// mirror floor to a new wall point, joined to the lens.
TEST(VeachPerturbationChiSquare, CausticFromAMirror) {
    Perturbed s(wallMirrorCeiling({0, 0.5, 0.5}));
    Ray ray;
    const MltVertex lens = s.lens(&ray);
    const MltVertex light = s.light();
    // Towards the mirror point whose reflection reaches the wall at (0, 0, 3).
    ray = spawnRay(light.p, light.ng, normalize(Vec3(0, -1, 2) - light.p), 0);
    const MltVertex mirror = s.trace(ray, true);
    Ray next;
    ASSERT_TRUE(s.space().followSpecular(mirror, ray, true, TransportMode::Importance, next));
    const MltVertex wall = s.trace(next, false);
    s.x = {light, mirror, wall, lens};
    s.finish();
    const Perturbations& p = s.integrator->perturbations();
    ASSERT_TRUE(p.causticApplies(s.x));
    const Model& m = s.model;
    const Offsets offsets;
    auto t = [&](const MltPath& z) {
        const D3 l = of(z[0].p), mp = of(z[1].p), w = of(z[2].p);
        return angleJacobian(m, l, unit(mp - l), 1) * mirrorFactor(l, mp, w, m.rects[1].normal());
    };
    const double tx = t(s.x);
    const D3 w0 = unit(of(mirror.p) - of(light.p));
    const Window window{&m.rects[0], of(wall.p), 0.3};
    check(
        "caustic perturbation, mirror onto a wall", window, 1000000,
        [&](Rng& rng, ScratchBuffer& a, PathStats& st, MltPath& y, double* ratio) {
            return p.caustic(s.x, rng, a, st, y, ratio);
        },
        [&](Rng& rng) -> std::optional<D3> {
            auto c = m.chain(m.light, offsets.direction(rng, w0), 1);
            if (!c || !m.visible(c->back(), {})) return {};
            return c->back();
        },
        [&](const MltPath& y) { return tx / t(y); }, 2);
}

// Caustic perturbation from a distant light, L S D E (path_space.h: x0 a direction): the
// direction stays and the ray's point on the disk at infinity moves by the documented offset
// (length in [1e-4, 0.1] times the scene's radius, density proportional to 1 / length), the
// parallel ray reflects in a mirror floor to a new point of a wall, joined to the lens. T's
// Jacobian in the pseudo-measure: disk area to the wall's by finite differences of the model,
// times the mirror's factor with A at infinity, the limit |cos at M| / |MB|^2 of the one above.
TEST(VeachPerturbationChiSquare, CausticFromADistantLightInAMirror) {
    Model model;
    model.rects = {{{-3, -3, 3}, {6, 0, 0}, {0, 6, 0}, false}, {{-2, -1, 0.5}, {4, 0, 0}, {0, 0, 2}, true}};
    const D3 d = unit({0, -1, 1});
    model.distant = d;
    Perturbed s(model);
    Ray ray;
    const MltVertex lens = s.lens(&ray);
    const MltVertex light = s.light();
    ASSERT_TRUE(atInfinity(light));
    ASSERT_NEAR(light.ng.z, d.z, 1e-6);
    // The parallel ray that meets the mirror at (0, -1, 2) and the wall at (0, 0, 3).
    const D3 o0 = D3{0, -1, 2} - 10.0 * d;
    ray = Ray{Vec3(float(o0.x), float(o0.y), float(o0.z)), light.ng};
    const MltVertex mirror = s.trace(ray, true);
    Ray next;
    ASSERT_TRUE(s.space().followSpecular(mirror, ray, true, TransportMode::Importance, next));
    const MltVertex wall = s.trace(next, false);
    s.x = {light, mirror, wall, lens};
    s.finish();
    const Perturbations& p = s.integrator->perturbations();
    ASSERT_TRUE(p.causticApplies(s.x));
    const Model& m = s.model;
    const D3 t1 = unit(cross(d, {1, 0, 0})), s1 = cross(d, t1);
    auto t = [&](const MltPath& z) {
        const D3 mp = of(z[1].p), w = of(z[2].p), o = mp - 10.0 * d;
        const double area = jacobian([&](double a, double b) { return m.chain(o + a * t1 + b * s1, d, 1)->back(); }, 1e-4);
        const double db = norm(w - mp);
        return area * std::fabs(dot(m.rects[1].normal(), d)) / (db * db);
    };
    const double tx = t(s.x);
    const double R = s.scene->boundsRadius();
    const Window window{&m.rects[0], of(wall.p), 0.3};
    check(
        "caustic perturbation, distant light, mirror onto a wall", window, 1000000,
        [&](Rng& rng, ScratchBuffer& a, PathStats& st, MltPath& y, double* ratio) {
            return p.caustic(s.x, rng, a, st, y, ratio);
        },
        [&](Rng& rng) -> std::optional<D3> {
            const double r = R * 1e-4 * std::pow(0.1 / 1e-4, rng.uniformDouble()), phi = 2 * kPi * rng.uniformDouble();
            auto c = m.chain(o0 + r * std::cos(phi) * t1 + r * std::sin(phi) * s1, d, 1);
            if (!c || !m.visible(c->back(), {})) return {};
            return c->back();
        },
        [&](const MltPath& y) { return tx / t(y); }, 2);
}

// Multi-chain perturbation, L D S D E: the film point moves to a new wall point; the direction
// leaving it (the old one, perturbed) reflects in the mirror floor to a new ceiling point,
// joined to the light.
TEST(VeachPerturbationChiSquare, MultiChainThroughAMirror) {
    Perturbed s(wallMirrorCeiling({0, 0.3, 0.8}));
    Ray ray;
    const MltVertex lens = s.lens(&ray);
    const MltVertex wall = s.trace(ray, false);
    ray = spawnRay(wall.p, wall.ng, normalize(Vec3(0, -1, 2) - wall.p), 0);
    const MltVertex mirror = s.trace(ray, true);
    Ray next;
    ASSERT_TRUE(s.space().followSpecular(mirror, ray, true, TransportMode::Radiance, next));
    const MltVertex ceiling = s.trace(next, false);
    s.x = {s.light(), ceiling, mirror, wall, lens};
    s.finish();
    const Perturbations& p = s.integrator->perturbations();
    ASSERT_TRUE(p.multiChainApplies(s.x));
    const Model& m = s.model;
    const Offsets offsets;
    auto t = [&](const MltPath& z) {
        const D3 w = of(z[3].p), mp = of(z[2].p), c = of(z[1].p);
        return filmJacobian(m, w - of(z[4].p), 0) * angleJacobian(m, w, unit(mp - w), 1) *
               mirrorFactor(w, mp, c, m.rects[1].normal());
    };
    const double tx = t(s.x);
    const D3 w0 = unit(of(mirror.p) - of(wall.p));
    const Window window{&m.rects[2], of(ceiling.p), 0.3};
    check(
        "multi-chain perturbation, wall then mirror onto a ceiling", window, 1000000,
        [&](Rng& rng, ScratchBuffer& a, PathStats& st, MltPath& y, double* ratio) {
            return p.lens(s.x, s.rasterX, rng, a, st, y, ratio);
        },
        [&](Rng& rng) -> std::optional<D3> {
            double qx, qy;
            offsets.film(rng, s.rasterX.x, s.rasterX.y, &qx, &qy);
            auto w = m.chain({}, filmRay(qx, qy), 0);
            if (!w) return {};
            auto c = m.chain(w->back(), offsets.direction(rng, w0), 1);
            if (!c || !m.visible(c->back(), m.light)) return {};
            return c->back();
        },
        [&](const MltPath& y) { return tx / t(y); }, 1);
}
