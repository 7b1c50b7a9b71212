// The transition densities of Veach's mutations against the mutations' own sampling: on a
// scene small enough to bin (a light quad over a floor, a back wall, a pinhole), the
// vertices a mutation really proposes are histogrammed over a surface and compared, by a
// chi-square test, with the density T(x -> y) the acceptance uses, integrated over each bin.
// A T that is off by a constant factor, misses a split of the bidirectional mutation, or
// weights one side's density wrongly, fails here even where the image tests' 4 sigma would
// need far longer renders to see it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "../materials/stats.h"
#include "mc/estimator.h"
#include "render_helpers.h"
#include "temp_images.h"
#include "transport/mlt/veach/veach_mlt.h"

using namespace ps;
using namespace ps::test;

namespace {

// Floor y = 0 and back wall z = 2, each [-2, 2] wide; a quad light at y = 1.5 facing down.
const char* kScene = R"(
    LookAt 0 1 -3  0 0.6 2  0 1 0
    Camera "perspective" "float fov" [ 60 ]
    Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
    PixelFilter "box"
    WorldBegin
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]
      Shape "bilinearmesh" "point3 P" [ -0.3 1.5 0.5   0.3 1.5 0.5   -0.3 1.5 1.1   0.3 1.5 1.1 ]
    AttributeEnd
    Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
    Shape "bilinearmesh" "point3 P" [ -2 0 2   2 0 2   -2 0 -2   2 0 -2 ]
    Shape "bilinearmesh" "point3 P" [ -2 0 2   -2 2 2   2 0 2   2 2 2 ]
)";

// Which surface a histogram covers: the floor (bins over x, z) or the wall (bins over x, y).
enum class Surface { Floor, Wall };
constexpr int kBins = 12;

struct PathSetup {
    std::unique_ptr<Scene> scene;
    std::unique_ptr<VeachMLTIntegrator> integrator;
    ScratchBuffer arena;
    MltPath x;  // light, floor, wall, lens

    // With `travel` non-zero, x0 is the scene's light at infinity instead, its light
    // travelling along `travel` (a distant light's own direction whatever `travel` says).
    explicit PathSetup(const std::string& text = kScene, Vec3 travel = Vec3()) {
        setWarningsQuiet(true);
        scene = buildScene(parseSceneString(text, ".", "<test>"));
        integrator = std::make_unique<VeachMLTIntegrator>(*scene, 5, MetropolisParams{});
        const PathSpace& space = integrator->space();
        PathStats stats;
        Rng rng(3);
        std::vector<MltVertex> light;
        EXPECT_TRUE(space.walk(light, 1, TransportMode::Importance, 0.0f, {}, rng, arena, stats));
        MltVertex lens, wall, floor;
        Ray ray = space.cameraRay(Vec2(16.5f, 9.5f), Vec2(0.5f, 0.5f), 0.0f, {}, &lens);
        // Through a medium (kFoggyScene) without flights: the vertices know their medium.
        EXPECT_TRUE(space.trace(ray, {}, arena, stats, wall, false, space.mediumFrom(lens, ray.d)));
        EXPECT_NEAR(wall.p.z, 2.0f, 1e-3f) << "the pixel must see the wall";
        const Ray toFloor = spawnRay(wall.p, wall.ng, normalize(Vec3(0.2f, 0, 0.8f) - wall.p), 0);
        EXPECT_TRUE(space.trace(toFloor, {}, arena, stats, floor, false, space.mediumFrom(wall, toFloor.d)));
        EXPECT_NEAR(floor.p.y, 0.0f, 1e-3f);
        x = {light[0], floor, wall, lens};
        if (travel.x != 0 || travel.y != 0 || travel.z != 0) {
            MltVertex& x0 = x[0];
            x0 = MltVertex();
            x0.kind = MltVertex::Kind::Light;
            for (const auto& l : scene->lights())
                if (l->atInfinity()) x0.light = l.get();
            EXPECT_TRUE(x0.light != nullptr);
            x0.delta = x0.light->isDelta();
            if (x0.delta) travel = x0.light->sampleLe(Vec2(0.5f, 0.5f), Vec2(0.5f, 0.5f), nullptr)->ray.d;
            x0.ng = x0.ns = normalize(travel);
            EXPECT_TRUE(atInfinity(x0));
        }
        Vec2 raster;
        EXPECT_GT(space.contribution(x, &raster).luminance(), 0.0f);
    }

    // x with vertex i moved to point (u, v) of the surface (traced from just in front of it),
    // or nothing if the point cannot be joined to its neighbours.
    MltPath moved(int i, Surface s, float u, float v, ScratchBuffer& a) const {
        PathStats stats;
        MltVertex hit;
        const Ray ray = s == Surface::Floor ? Ray{Vec3(u, 1, v), Vec3(0, -1, 0)} : Ray{Vec3(u, v, 1), Vec3(0, 0, 1)};
        MltPath y = x;
        if (!integrator->space().trace(ray, {}, a, stats, hit, false, integrator->space().mediumFrom(x[size_t(i + 1)], ray.d)))
            return {};
        y[size_t(i)] = hit;
        // A proposal reaches the point only along unblocked edges (the ray that made it and
        // the join to the other side).
        const PathSpace& space = integrator->space();
        if (!space.visible(y[size_t(i - 1)], hit, stats) || !space.visible(hit, y[size_t(i + 1)], stats)) return {};
        return y;
    }
};

int binOf(Surface s, Vec3 p) {
    const bool on = s == Surface::Floor ? std::fabs(p.y) < 1e-3f : std::fabs(p.z - 2) < 1e-3f;
    const float u = p.x, v = s == Surface::Floor ? p.z : p.y;
    const float v0 = s == Surface::Floor ? -2 : 0, vSize = s == Surface::Floor ? 4 : 2;
    if (!on || u < -2 || u >= 2 || v < v0 || v >= v0 + vSize) return -1;
    return std::min(kBins - 1, int((u + 2) / 4 * kBins)) * kBins + std::min(kBins - 1, int((v - v0) / vSize * kBins));
}

// Expected counts of `proposals` draws per bin: the integral of density(y) over the bin,
// y being x with vertex i moved over the surface, by Monte Carlo over random points (its
// variance goes into the chi-square's denominator).
void expectedCounts(const PathSetup& s, int i, Surface surface, double proposals,
                    const std::function<double(const MltPath&)>& density, std::vector<double>& mean,
                    std::vector<double>& variance) {
    const int points = 256;
    const float vSize = surface == Surface::Floor ? 4 : 2, v0 = surface == Surface::Floor ? -2 : 0;
    const double binArea = (4.0 / kBins) * (vSize / kBins);
    Rng rng(17);
    ScratchBuffer arena;
    mean.assign(kBins * kBins, 0);
    variance.assign(kBins * kBins, 0);
    for (int bu = 0; bu < kBins; ++bu)
        for (int bv = 0; bv < kBins; ++bv) {
            RunningStats t;
            for (int k = 0; k < points; ++k) {
                arena.reset();
                const float u = -2 + 4.0f * (bu + rng.uniform()) / kBins, v = v0 + vSize * (bv + rng.uniform()) / kBins;
                const MltPath y = s.moved(i, surface, u, v, arena);
                t.add(y.empty() ? 0.0 : density(y) * binArea * proposals);
            }
            mean[size_t(bu * kBins + bv)] = t.mean();
            variance[size_t(bu * kBins + bv)] = t.standardError() * t.standardError();
        }
}

void expectFit(const char* what, const std::vector<double>& observed, const std::vector<double>& expected,
               const std::vector<double>& variance) {
    double o = 0, e = 0, ev = 0;
    for (size_t k = 0; k < observed.size(); ++k) o += observed[k], e += expected[k], ev += variance[k];
    ChiSquareResult r = chiSquare(observed, expected, variance);
    if (std::getenv("PS_DEBUG_BINS"))
        for (int i = 0; i < kBins; ++i) {
            for (int j = kBins - 1; j >= 0; --j) std::printf("%6.0f/%-6.0f ", observed[size_t(i * kBins + j)], expected[size_t(i * kBins + j)]);
            std::printf("\n");
        }
    // The bins' shape by chi-square, and their total (which Pearson's statistic barely sees:
    // a T off by a constant factor) within 4 sigma: Poisson counts plus the integral's error.
    const double z = (o - e) / std::sqrt(e + ev);
    std::printf("[ %s ] %.0f proposals binned, %.1f expected (%.2f sigma); chi2 %.1f on %d dof, p = %.3g\n", what, o, e, z,
                r.chi2, r.dof, r.pValue);
    EXPECT_GT(r.pValue, 1e-4) << what;
    EXPECT_LT(std::fabs(z), 4.0) << what;
    EXPECT_GT(o, 5000) << what << ": too few proposals land in the bins";
}

bool same(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

}  // namespace

// The bidirectional mutation, replacing x's floor vertex (its light side is x0 alone, which
// a walk cannot continue: the new vertex comes from the camera side, scattered at the wall)
// or its wall vertex (half from a light walk scattered at the floor, half from a camera
// ray, through deleting the wall vertex alone or the wall vertex and the lens).
void expectBidirectionalDensity(const std::string& scene, const std::string& tag) {
    PathSetup s(scene);
    const BidirectionalMutation& bd = s.integrator->bidirectional();
    const int n = 3000000;
    std::vector<double> floorObserved(kBins * kBins, 0), wallObserved(kBins * kBins, 0);
    ScratchBuffer arena;
    PathStats stats;
    Rng rng(5);
    MltPath y;
    int mismatched = 0;
    for (int k = 0; k < n; ++k) {
        double txy = 0, tyx = 0;
        if (!bd.propose(s.x, rng, arena, stats, y, &txy, &tyx)) continue;
        if (y.size() != 4 || !same(y[0].p, s.x[0].p) || !same(y[3].p, s.x[3].p)) continue;
        const bool floorMoved = !same(y[1].p, s.x[1].p), wallMoved = !same(y[2].p, s.x[2].p);
        if (floorMoved == wallMoved) continue;
        // What propose reports is the transition density of the choice it made.
        const double expected = floorMoved ? bd.transition(s.x, y, 1, 1, 1) : txy;
        if (floorMoved && !(std::fabs(txy - expected) <= 1e-9 * expected)) ++mismatched;
        const int b = binOf(floorMoved ? Surface::Floor : Surface::Wall, y[floorMoved ? 1 : 2].p);
        if (b >= 0) (floorMoved ? floorObserved : wallObserved)[size_t(b)] += 1;
    }
    EXPECT_EQ(mismatched, 0);
    std::vector<double> e, v;
    expectedCounts(s, 1, Surface::Floor, n, [&](const MltPath& z) { return bd.transition(s.x, z, 1, 1, 1); }, e, v);
    expectFit(("bidirectional, floor vertex" + tag).c_str(), floorObserved, e, v);
    expectedCounts(s, 2, Surface::Wall, n,
                   [&](const MltPath& z) { return bd.transition(s.x, z, 2, 1, 1) + bd.transition(s.x, z, 2, 2, 2); }, e, v);
    expectFit(("bidirectional, wall vertex" + tag).c_str(), wallObserved, e, v);
}

TEST(VeachTransition, BidirectionalMutationProposesWithItsDensity) { expectBidirectionalDensity(kScene, ""); }

// The same in fog around everything (Veach's mlt with media, path_space_media.cpp): a walk's
// flight may stop in the fog (those proposals are not binned), and T of a surface vertex
// includes the probability exp(-integral of the majorant) that its flight reached it.
TEST(VeachTransition, BidirectionalMutationProposesWithItsDensityInFog) {
    const std::string fog = R"(
    MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0.1 0.1 0.1 ] "rgb sigma_s" [ 0.15 0.25 0.2 ]
    MediumInterface "" "fog"
)";
    std::string scene = fog + kScene;
    scene.replace(scene.find("WorldBegin"), 10, "WorldBegin\n    MediumInterface \"fog\" \"fog\"");
    expectBidirectionalDensity(scene, " in fog");
}

// The lens subpath mutation: a new camera ray through a uniform film point replaces the
// lens subpath (the lens and the wall vertex); T is the camera side's density of the new
// wall vertex, and the ratio it reports is T(y -> x) / T(x -> y).
TEST(VeachTransition, LensSubpathMutationProposesWithItsDensity) {
    PathSetup s;
    const LensSubpathMutation& ls = s.integrator->lensSubpath();
    const PathSpace& space = s.integrator->space();
    ASSERT_TRUE(ls.applies(s.x));
    const int n = 400000;
    std::vector<double> observed(kBins * kBins, 0);
    ScratchBuffer arena;
    PathStats stats;
    Rng rng(9);
    MltPath y;
    int ratiosOff = 0;
    for (int k = 0; k < n; ++k) {
        double ratio = 0;
        if (!ls.propose(s.x, rng, arena, stats, y, &ratio)) continue;
        ASSERT_EQ(y.size(), 4u);
        const double forward = space.cameraDensity(y, 2), backward = space.cameraDensity(s.x, 2);
        if (!(std::fabs(ratio - backward / forward) <= 1e-4 * ratio)) ++ratiosOff;
        const int b = binOf(Surface::Wall, y[2].p);
        if (b >= 0) observed[size_t(b)] += 1;
    }
    EXPECT_EQ(ratiosOff, 0);
    std::vector<double> e, v;
    expectedCounts(s, 2, Surface::Wall, n, [&](const MltPath& z) { return space.cameraDensity(z, 2); }, e, v);
    expectFit("lens subpath, wall vertex", observed, e, v);
}

// The bidirectional mutation's floor vertex scattered at a smooth-coated wall: the path
// space's own mixture there (MltVertex::mixed), the coating's mirror with probability R(wo),
// else a cosine lobe of density (1 - R) cos / pi, which T must carry. Proposals that took the
// mirror (a delta: the wall turns specular in y) are left out of the bins, as their part is
// of the expected counts.
TEST(VeachTransition, BidirectionalMutationProposesWithItsDensityThroughACoating) {
    std::string text = kScene;
    const std::string wall = R"(Shape "bilinearmesh" "point3 P" [ -2 0 2   -2 2 2   2 0 2   2 2 2 ])";
    text.replace(text.find(wall), 0, "Material \"coateddiffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n    ");
    PathSetup s(text);
    ASSERT_TRUE(s.x[2].mixed);
    const BidirectionalMutation& bd = s.integrator->bidirectional();
    const int n = 1500000;
    std::vector<double> observed(kBins * kBins, 0);
    ScratchBuffer arena;
    PathStats stats;
    Rng rng(5);
    MltPath y;
    int mirrored = 0;
    for (int k = 0; k < n; ++k) {
        double txy = 0, tyx = 0;
        if (!bd.propose(s.x, rng, arena, stats, y, &txy, &tyx)) continue;
        if (y.size() != 4 || !same(y[0].p, s.x[0].p) || !same(y[2].p, s.x[2].p) || !same(y[3].p, s.x[3].p) ||
            same(y[1].p, s.x[1].p))
            continue;
        if (y[2].delta) {
            ++mirrored;
            continue;
        }
        const int b = binOf(Surface::Floor, y[1].p);
        if (b >= 0) observed[size_t(b)] += 1;
    }
    std::printf("[ bidirectional through a coating ] %d proposals took the coating's mirror\n", mirrored);
    std::vector<double> e, v;
    expectedCounts(s, 1, Surface::Floor, n, [&](const MltPath& z) { return bd.transition(s.x, z, 1, 1, 1); }, e, v);
    expectFit("bidirectional, floor vertex through a coating", observed, e, v);
}

namespace {

// The transition tests' scene with a light at infinity added: an image infinite light (a
// dim map with two bright spots, +z of the map turned to +y) or a distant light.
std::string withLightAtInfinity(const std::string& light) {
    std::string text = kScene;
    text.replace(text.find("WorldBegin") + 10, 0, "\n" + light + "\n");
    return text;
}

// Equal-area bins over the sphere of directions: z = cos theta by rows, phi by columns.
int directionBin(Vec3 w) {
    const float phi = std::atan2(w.y, w.x) + float(kPi);
    return std::min(kBins - 1, int((w.z + 1) / 2 * kBins)) * kBins + std::min(kBins - 1, int(phi / (2 * kPi) * kBins));
}

}  // namespace

// The bidirectional mutation replacing a light vertex at infinity (a direction, in the
// solid-angle measure: path_space.h) and nothing else: the new direction comes from the
// camera side (the floor's cosine lobe, a ray that escapes) or from the light side (the
// image light's own distribution, joined to the floor by a shadow ray along it); T sums
// both. Histogrammed over the sphere against T integrated over each bin.
TEST(VeachTransition, BidirectionalMutationProposesADirectionAtInfinityWithItsDensity) {
    TempImages tmp("veach-transition-sky");
    Image map(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) map.set(x, y, Spectrum((x == 3 && y == 4) || (x == 1 && y == 2) ? 60.0f : 0.3f));
    const std::string light = "AttributeBegin\nRotate -90 1 0 0\nLightSource \"infinite\" \"string filename\" [ \"" +
                              tmp.write("sky.pfm", map) + "\" ]\nAttributeEnd";
    PathSetup s(withLightAtInfinity(light), Vec3(0.3f, -1, 0.2f));
    const BidirectionalMutation& bd = s.integrator->bidirectional();
    const PathSpace& space = s.integrator->space();
    const int n = 1500000;
    std::vector<double> observed(kBins * kBins, 0);
    ScratchBuffer arena;
    PathStats stats;
    Rng rng(21);
    MltPath y;
    for (int k = 0; k < n; ++k) {
        double txy = 0, tyx = 0;
        if (!bd.propose(s.x, rng, arena, stats, y, &txy, &tyx)) continue;
        // (Replacing the pinhole alone gives x again: its direction must have moved.)
        if (y.size() != 4 || !atInfinity(y[0]) || same(y[0].ng, s.x[0].ng) || !same(y[1].p, s.x[1].p) ||
            !same(y[2].p, s.x[2].p) || !same(y[3].p, s.x[3].p))
            continue;
        observed[size_t(directionBin(-y[0].ng))] += 1;
    }
    // T over each bin: uniform directions within it (solid angle 4 pi / kBins^2 each).
    std::vector<double> e(kBins * kBins, 0), v(kBins * kBins, 0);
    Rng urng(17);
    const double binSolidAngle = 4 * kPi / (kBins * kBins);
    for (int bz = 0; bz < kBins; ++bz)
        for (int bp = 0; bp < kBins; ++bp) {
            RunningStats t;
            for (int k = 0; k < 256; ++k) {
                const float z = -1 + 2 * (bz + urng.uniform()) / kBins;
                const float phi = float(2 * kPi) * (bp + urng.uniform()) / kBins - float(kPi);
                const float r = std::sqrt(std::max(0.0f, 1 - z * z));
                const Vec3 toLight(r * std::cos(phi), r * std::sin(phi), z);
                MltPath z2 = s.x;
                z2[0].ng = z2[0].ns = -toLight;
                const bool joins = space.visible(z2[0], z2[1], stats);
                t.add(joins ? bd.transition(s.x, z2, 0, 1, 1) * binSolidAngle * n : 0.0);
            }
            e[size_t(bz * kBins + bp)] = t.mean();
            v[size_t(bz * kBins + bp)] = t.standardError() * t.standardError();
        }
    expectFit("bidirectional, direction at infinity", observed, e, v);
}

// The bidirectional mutation replacing the floor vertex after a distant light (a delta
// direction): from the camera side (scattered at the wall, joined along the light's
// direction), or, when x0 is replaced too, from the disk at infinity (its area density
// times |cos| at the floor); T sums both ways.
TEST(VeachTransition, BidirectionalMutationProposesAVertexLitFromInfinityWithItsDensity) {
    PathSetup s(withLightAtInfinity("LightSource \"distant\" \"point3 from\" [ 0.4 1 -0.3 ] \"point3 to\" [ 0 0 0 ] "
                                    "\"rgb L\" [ 3 3 3 ]"),
                Vec3(0, -1, 0));
    const BidirectionalMutation& bd = s.integrator->bidirectional();
    const int n = 6000000;
    std::vector<double> observed(kBins * kBins, 0);
    ScratchBuffer arena;
    PathStats stats;
    Rng rng(23);
    MltPath y;
    for (int k = 0; k < n; ++k) {
        double txy = 0, tyx = 0;
        if (!bd.propose(s.x, rng, arena, stats, y, &txy, &tyx)) continue;
        if (y.size() != 4 || y[0].light != s.x[0].light || same(y[1].p, s.x[1].p) || !same(y[2].p, s.x[2].p) ||
            !same(y[3].p, s.x[3].p))
            continue;
        const int b = binOf(Surface::Floor, y[1].p);
        if (b >= 0) observed[size_t(b)] += 1;
    }
    std::vector<double> e, v;
    expectedCounts(s, 1, Surface::Floor, n,
                   [&](const MltPath& z) { return bd.transition(s.x, z, 0, 2, 2) + bd.transition(s.x, z, 1, 1, 1); }, e, v);
    expectFit("bidirectional, floor vertex lit from infinity", observed, e, v);
}

namespace {

// The scene through a wide thin lens (radius 0.8) close over the floor, focused on the floor
// point it looks at (so that every lens point sees it; the lens cosine falls to 0.85 at the
// rim).
std::string lensScene() {
    std::string text = kScene;
    const std::string camera = R"(LookAt 0 1 -3  0 0.6 2  0 1 0
    Camera "perspective" "float fov" [ 60 ])";
    return text.replace(text.find(camera), camera.size(), R"(LookAt 0 0.8 0  0 0 1  0 1 0
    Camera "perspective" "float fov" [ 60 ] "float lensradius" [ 0.8 ] "float focaldistance" [ 1.28062 ])");
}

}  // namespace

// The t = 0 strategy (thesis §10.2) on x = light, floor, lens through a thin lens: the lens
// points that rays scattered at the floor cross (PathSpace::reachLens), histogrammed over the
// disk against the light-side density lightDensity(y, 2) integrated over each bin; and the
// bidirectional mutation replacing the lens alone, from the camera side (a uniform lens point)
// or from the light side (t = 0), against T, which must sum both splits.
TEST(VeachTransition, LensVertexFromTheLightSideHasItsDensity) {
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(lensScene(), ".", "<test>"));
    VeachMLTIntegrator integrator(*scene, 5, MetropolisParams{});
    const PathSpace& space = integrator.space();
    const BidirectionalMutation& bd = integrator.bidirectional();
    ASSERT_TRUE(space.lensReachable());
    ScratchBuffer arena;
    PathStats stats;
    Rng rng(3);
    std::vector<MltVertex> light;
    ASSERT_TRUE(space.walk(light, 1, TransportMode::Importance, 0.0f, {}, rng, arena, stats));
    MltVertex lens, floor;
    const Ray ray = space.cameraRay(Vec2(16, 16), Vec2(0.5f, 0.5f), 0.0f, {}, &lens);
    ASSERT_TRUE(space.trace(ray, {}, arena, stats, floor));
    ASSERT_NEAR(floor.p.z, 1.0f, 1e-3f);
    const MltPath x = {light[0], floor, lens};
    Vec2 raster;
    ASSERT_GT(space.contribution(x, &raster).luminance(), 0.0f);

    // Bins over the square around the disk, in the lens plane's frame.
    const float r = 0.8f;
    const Vec3 f = scene->camera().forward(0), e1 = normalize(cross(f, Vec3(0, 1, 0))), e2 = cross(f, e1);
    auto binOfLens = [&](Vec3 p) {
        const Vec3 d = p - lens.p;
        const float a = dot(d, e1), b = dot(d, e2);
        EXPECT_LT(std::fabs(dot(d, f)), 1e-4f) << "off the lens plane";
        return std::min(kBins - 1, int((a + r) / (2 * r) * kBins)) * kBins + std::min(kBins - 1, int((b + r) / (2 * r) * kBins));
    };
    // (1024 points a bin: the bins the rim cuts need them.)
    auto expected = [&](double proposals, const std::function<double(const MltPath&)>& density, std::vector<double>& e,
                        std::vector<double>& v) {
        Rng urng(17);
        const double binArea = (2 * r / kBins) * (2 * r / kBins);
        e.assign(kBins * kBins, 0);
        v.assign(kBins * kBins, 0);
        for (int ba = 0; ba < kBins; ++ba)
            for (int bb = 0; bb < kBins; ++bb) {
                RunningStats t;
                for (int k = 0; k < 1024; ++k) {
                    const float a = -r + 2 * r * (ba + urng.uniform()) / kBins, b = -r + 2 * r * (bb + urng.uniform()) / kBins;
                    MltPath y = x;
                    y[2].p = lens.p + e1 * a + e2 * b;
                    t.add(a * a + b * b <= r * r ? density(y) * binArea * proposals : 0.0);
                }
                e[size_t(ba * kBins + bb)] = t.mean();
                v[size_t(ba * kBins + bb)] = t.standardError() * t.standardError();
            }
    };

    const int n = 200000;
    std::vector<double> observed(kBins * kBins, 0), e, v;
    for (int k = 0; k < n; ++k) {
        arena.reset();
        std::vector<MltVertex> side = {x[0], x[1]};
        PathSpace::rebind(side[1], arena);
        if (space.reachLens(side, rng, arena, stats)) observed[size_t(binOfLens(side[2].p))] += 1;
    }
    expected(n, [&](const MltPath& y) { return space.lightDensity(y, 2); }, e, v);
    expectFit("t = 0: lens vertex from the light side", observed, e, v);

    const int m = 400000;
    observed.assign(kBins * kBins, 0);
    MltPath y;
    for (int k = 0; k < m; ++k) {
        double txy = 0, tyx = 0;
        if (!bd.propose(x, rng, arena, stats, y, &txy, &tyx)) continue;
        if (y.size() != 3 || !same(y[0].p, x[0].p) || !same(y[1].p, x[1].p)) continue;
        observed[size_t(binOfLens(y[2].p))] += 1;
    }
    expected(m, [&](const MltPath& z) { return bd.transition(x, z, 2, 1, 1); }, e, v);
    expectFit("bidirectional, lens vertex from either side", observed, e, v);
}
