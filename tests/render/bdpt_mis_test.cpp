// BDPT's multiple importance sampling, checked on random paths: for a path found by a
// connection, rebuild every other way (s', t') of sampling the same vertices, with the
// densities computed afresh from the whole path, and check that (1) the weights of all
// strategies that can produce it sum to 1 (thesis eq. 9.4's condition for an unbiased
// combination) and (2) the weight BDPT computed from its subpaths' incrementally stored
// densities equals the freshly computed one; for every heuristic of thesis ch. 9 (mc/mis.h).
#include <gtest/gtest.h>

#include <new>
#include <string>
#include <vector>

#include "mc/sampler.h"
#include "render_helpers.h"
#include "transport/bdpt.h"

using namespace ps;
using namespace ps::test;

namespace {

// `lensradius` of the thin-lens variant (the t = 0 strategy), inserted after the camera.
std::string withLens(const char* scene) {
    std::string text = scene;
    const std::string camera = "Camera \"perspective\" \"float fov\" [ 30 ]";
    text.insert(text.find(camera) + camera.size(), " \"float lensradius\" [ 0.3 ] \"float focaldistance\" [ 2 ]");
    return text;
}

const char* kScene = R"(
    LookAt 0 0.5 2.2  0 0.5 0  0 1 0
    Camera "perspective" "float fov" [ 30 ]
    Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
    Integrator "bdpt" "integer maxdepth" [ 6 ]
    WorldBegin
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 6 6 6 ]
      Shape "bilinearmesh" "point3 P" [ -0.2 0.99 -0.2   0.2 0.99 -0.2   -0.2 0.99 0.2   0.2 0.99 0.2 ]
    AttributeEnd
    LightSource "point" "rgb I" [ 0.5 0.5 0.5 ] "point3 from" [ 0.3 0.7 0.2 ]
    Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 0 -0.5   0.5 0 -0.5 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 1 -0.5   0.5 1 -0.5   -0.5 1 0.5   0.5 1 0.5 ]
    Material "conductor" "rgb reflectance" [ 0.8 0.8 0.8 ] "float roughness" [ 0.3 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ]
    Material "conductor" "rgb reflectance" [ 0.9 0.9 0.9 ] "float roughness" [ 0 ]
    Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   -0.5 0 -0.5   -0.5 1 0.5   -0.5 1 -0.5 ]
    Material "diffuse" "rgb reflectance" [ 0.1 0.7 0.1 ]
    Shape "bilinearmesh" "point3 P" [ 0.5 0 -0.5   0.5 0 0.5   0.5 1 -0.5   0.5 1 0.5 ]
)";

PathVertex* allocPath(ScratchBuffer& scratch, int n) {
    auto* p = static_cast<PathVertex*>(scratch.allocBytes(sizeof(PathVertex) * size_t(n), alignof(PathVertex)));
    for (int i = 0; i < n; ++i) new (&p[i]) PathVertex();
    return p;
}

// Sample i's camera and light subpaths on a 32 x 32 film, as BDPT builds them.
struct SubpathPair {
    PathVertex* camera;
    PathVertex* light;
    int nCamera, nLight;
};
SubpathPair tracePair(const Scene& scene, const Subpaths& paths, Sampler& sampler, ScratchBuffer& scratch,
                      PathStats& stats, int i, LensHits* lens = nullptr) {
    int px = i % 32, py = (i / 32) % 32;
    sampler.startPixelSample(px, py, i);
    CameraSample cs{{px + sampler.get1D(), py + sampler.get1D()}, {0.5f, 0.5f}};
    Ray ray = scene.camera().generateRay(cs);
    SubpathPair p{allocPath(scratch, paths.maxCameraVertices()), allocPath(scratch, paths.maxLightVertices()), 0, 0};
    p.nCamera = paths.cameraSubpath(ray, sampler, scratch, stats, p.camera);
    p.nLight = paths.lightSubpath(sampler, 0.0f, scratch, stats, p.light, nullptr, nullptr, lens);
    return p;
}

// A specular scattering's delta density in the MIS ratios: a unit density per solid angle,
// converted to area like any other (thesis §10.3.5: forward and reverse deltas cancel).
constexpr float kDeltaDensity = 1;

// The full path y_0 (on a light) ... y_k (the camera) with densities of both walks.
struct FullPath {
    std::vector<PathVertex> y;
    std::vector<float> pLight, pCamera;  // area densities of y_i from the light / camera walk
};

FullPath rebuild(const Subpaths& paths, const PathVertex* light, int s, const PathVertex* camera, int t) {
    FullPath fp;
    for (int i = 0; i < s; ++i) fp.y.push_back(light[i]);
    for (int j = t - 1; j >= 0; --j) fp.y.push_back(camera[j]);
    int k = int(fp.y.size()) - 1;
    fp.pLight.assign(size_t(k + 1), 0.0f);
    fp.pCamera.assign(size_t(k + 1), 0.0f);
    std::vector<PathVertex>& y = fp.y;
    for (PathVertex& v : y) v.mode = TransportMode::Importance;
    fp.pLight[0] = paths.pdfLightOrigin(y[0], y[1]);
    fp.pLight[1] = paths.pdfLight(y[0], y[1]);
    for (int i = 1; i < k; ++i)
        fp.pLight[size_t(i + 1)] = y[size_t(i)].delta ? kDeltaDensity * areaFactor(y[size_t(i)], y[size_t(i + 1)])
                                                      : paths.pdf(y[size_t(i)], &y[size_t(i - 1)], y[size_t(i + 1)], false);
    for (PathVertex& v : y) v.mode = TransportMode::Radiance;
    fp.pCamera[size_t(k - 1)] = paths.pdf(y[size_t(k)], nullptr, y[size_t(k - 1)], false);
    for (int i = k - 1; i >= 1; --i)
        fp.pCamera[size_t(i - 1)] = y[size_t(i)].delta ? kDeltaDensity * areaFactor(y[size_t(i)], y[size_t(i - 1)])
                                                        : paths.pdf(y[size_t(i)], &y[size_t(i + 1)], y[size_t(i - 1)], false);
    return fp;
}

// Whether strategy (s', t') can sample this path at all.
bool possible(const BDPTIntegrator& bdpt, const FullPath& fp, int s) {
    int k = int(fp.y.size()) - 1, t = k + 1 - s;
    // t = 0: the light subpath reaches a thin lens, after a scattering vertex (k >= 2).
    if (t == 0) return bdpt.lensHits() && k >= 2;
    if (t < 1 || (s == 1 && t == 1)) return false;
    if (s == 0) return !fp.y[0].isDeltaLight();
    if (t == 1) return fp.y[size_t(k - 1)].connectible() && !fp.y[size_t(k - 1)].delta;
    const PathVertex& qs = fp.y[size_t(s - 1)];
    const PathVertex& pt = fp.y[size_t(s)];
    return !qs.delta && !pt.delta && (s == 1 || qs.connectible()) && pt.connectible();
}

float weightOf(const BDPTIntegrator& bdpt, const FullPath& fp, int s) {
    int k = int(fp.y.size()) - 1, t = k + 1 - s;
    std::vector<PathVertex> light(size_t(std::max(s, 1)));
    std::vector<PathVertex> camera(static_cast<size_t>(t));
    for (int i = 0; i < s; ++i) {
        light[size_t(i)] = fp.y[size_t(i)];
        if (fp.y[size_t(i)].kind != VertexKind::Camera) light[size_t(i)].mode = TransportMode::Importance;
        light[size_t(i)].pdfFwd = fp.pLight[size_t(i)];
        light[size_t(i)].pdfRev = fp.pCamera[size_t(i)];
    }
    // t = 0: the lens has no normal of its own, so its area density from the light walk takes
    // the lens cosine here (as BDPTIntegrator::connectLens gives it; camera subpaths keep the
    // reverse density without it, which lensRatio completes).
    if (t == 0) {
        const Camera& cam = bdpt.subpaths().scene().camera();
        light[size_t(k)].pdfFwd *= std::fabs(dot(cam.forward(0), normalize(fp.y[size_t(k - 1)].p - fp.y[size_t(k)].p)));
    }
    for (int j = 0; j < t; ++j) {
        camera[size_t(j)] = fp.y[size_t(k - j)];
        camera[size_t(j)].mode = TransportMode::Radiance;
        camera[size_t(j)].pdfFwd = fp.pCamera[size_t(k - j)];
        camera[size_t(j)].pdfRev = fp.pLight[size_t(k - j)];
    }
    return bdpt.misWeight(light.data(), camera.data(), nullptr, s, t);
}

class BdptMis : public ::testing::TestWithParam<const char*> {};

// Whether a heuristic's weight jumps where densities cross (cutoff, maximum): there the
// stored and the fresh densities, which differ by up to a percent (see below), may fall on
// either side of a threshold.
bool stepwise(const MisWeighting& w) {
    return w.heuristic == MisHeuristic::Cutoff || w.heuristic == MisHeuristic::Maximum;
}

}  // namespace

// "...#lens": through a thin lens, where the light subpaths' lens crossings are the t = 0
// strategy (lens_hits.h), whose weights are checked too.
TEST_P(BdptMis, WeightsOfAllStrategiesSumToOne) {
    setWarningsQuiet(true);
    std::string param = GetParam();
    const bool thinLens = param.size() > 5 && param.substr(param.size() - 5) == "#lens";
    if (thinLens) param.resize(param.size() - 5);
    SceneDescription desc = parseSceneString(thinLens ? withLens(kScene) : std::string(kScene), ".", "<test>");
    auto scene = buildScene(desc);
    const MisWeighting mis = parseMisWeighting(param);
    BDPTIntegrator bdpt(*scene, scene->settings().maxDepth, mis);
    ASSERT_EQ(bdpt.lensHits(), thinLens);
    const Subpaths& paths = bdpt.subpaths();
    auto sampler = createSampler("independent", 5, 1);
    ScratchBuffer scratch;
    PathStats stats;
    int checked = 0, withDelta = 0, deltaLight = 0, skipped = 0, stepped = 0, lensChecked = 0;
    for (int i = 0; i < (thinLens ? 40000 : 4000) && (checked < 600 || (thinLens && lensChecked < 200)); ++i) {
        LensHits lens;
        std::vector<LensHit> hits(size_t(paths.maxLightVertices()));
        lens.hits = hits.data();
        lens.capacity = thinLens ? int(hits.size()) : 0;
        auto [camera, light, nc, nl] = tracePair(*scene, paths, *sampler, scratch, stats, i, &lens);
        // The weights as the renderer computes them: from the running sums along each subpath.
        const auto prefixes = bdpt.misPrefixes(light, nl, camera, nc, scratch);
        // Through a thin lens the loop goes on for lens crossings (rarer): the connections stop
        // at the same count as through a pinhole.
        for (int t = 2; t <= (checked < 600 ? nc : 0); ++t)
            for (int s = 2; s <= nl; ++s) {
                if (s + t - 2 > paths.maxDepth()) continue;
                auto c = bdpt.connect(light, camera, s, t, *sampler, stats, true, &prefixes);
                if (c.L.isBlack()) continue;
                FullPath fp = rebuild(paths, light, s, camera, t);
                // Stored densities use the sampled directions, fresh ones the directions between
                // hit points, which differ by the ray-origin offsets: at vertices a few
                // millimetres apart (box corners) that changes area densities by a percent.
                bool close = false;
                for (size_t q = 1; q < fp.y.size(); ++q) close |= length(fp.y[q].p - fp.y[q - 1].p) < 0.05f;
                if (close) {
                    ++skipped;
                    continue;
                }
                double sum = 0;
                for (int sp = 0; sp <= int(fp.y.size()); ++sp)
                    if (possible(bdpt, fp, sp)) sum += weightOf(bdpt, fp, sp);
                EXPECT_NEAR(sum, 1.0, 2e-3) << "s " << s << " t " << t;
                const float fresh = weightOf(bdpt, fp, s);
                if (stepwise(mis) && std::abs(c.weight - fresh) > 2e-3f * std::max(1.0f, c.weight)) ++stepped;
                else EXPECT_NEAR(c.weight, fresh, 2e-3 * std::max(1.0f, c.weight)) << "s " << s << " t " << t;
                ++checked;
                for (const PathVertex& v : fp.y) withDelta += v.delta;
                deltaLight += fp.y[0].isDeltaLight();
            }
        // t = 0: each crossing of the lens, its path being the light subpath's and the lens.
        for (int h = 0; h < lens.n; ++h) {
            const LensHit& hit = lens.hits[h];
            if (hit.index - 1 > paths.maxDepth()) continue;
            auto c = bdpt.connectLens(light, hit, scratch, &prefixes);
            if (c.L.isBlack()) continue;
            std::vector<PathVertex> path(light, light + hit.index);
            PathVertex& v = path.emplace_back();
            v.kind = VertexKind::Camera;
            v.mode = TransportMode::Radiance;
            v.p = hit.lens.p;
            FullPath fp = rebuild(paths, path.data(), hit.index + 1, nullptr, 0);
            bool close = false;
            for (size_t q = 1; q < fp.y.size(); ++q) close |= length(fp.y[q].p - fp.y[q - 1].p) < 0.05f;
            if (close) continue;
            double sum = 0;
            for (int sp = 0; sp <= int(fp.y.size()); ++sp)
                if (possible(bdpt, fp, sp)) sum += weightOf(bdpt, fp, sp);
            EXPECT_NEAR(sum, 1.0, 2e-3) << "t = 0, s " << hit.index + 1;
            const float fresh = weightOf(bdpt, fp, hit.index + 1);
            if (stepwise(mis) && std::abs(c.weight - fresh) > 2e-3f * std::max(1.0f, c.weight)) ++stepped;
            else EXPECT_NEAR(c.weight, fresh, 2e-3 * std::max(1.0f, c.weight)) << "t = 0, s " << hit.index + 1;
            ++lensChecked;
        }
        scratch.reset();
    }
    if (thinLens) {
        std::printf("  %d lens crossings (t = 0) checked\n", lensChecked);
        EXPECT_GE(lensChecked, 100);
    }
    std::printf("  %d connected paths checked (%d specular vertices, %d from the point light), %d with vertices "
                "closer than 0.05 skipped\n",
                checked, withDelta, deltaLight, skipped);
    EXPECT_GE(checked, 200);
    EXPECT_LE(stepped, checked / 100) << "stored and fresh weights on either side of a step";
    EXPECT_GT(withDelta, 0);
    EXPECT_GT(deltaLight, 0);
}

// Power 2, balance and uniform take the prefix sums; the others the walk over every ratio.
INSTANTIATE_TEST_SUITE_P(Heuristics, BdptMis,
                         ::testing::Values("power", "balance", "none", "power:3", "power:0.5", "cutoff:0.1",
                                           "cutoff:0.5", "maximum", "power#lens", "balance#lens", "none#lens",
                                           "power:3#lens"),
                         [](const ::testing::TestParamInfo<const char*>& i) {
                             std::string name = i.param;
                             for (char& c : name)
                                 if (c == ':' || c == '.' || c == '#') c = '_';
                             return name == "none" ? std::string("uniform") : name;
                         });

// The walk over every strategy's ratio (weightFromEveryRatio, for the heuristics that are
// not sums of factoring terms) enumerates the strategies the prefix sums add up: with power
// 1 and cutoff 0, which are the balance heuristic computed by the walk, every strategy's
// weight of every connected path equals the balance heuristic's from the prefix sums.
TEST(BdptMis, EveryRatioWalkMatchesThePrefixSums) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(kScene, ".", "<test>");
    auto scene = buildScene(desc);
    const int maxDepth = scene->settings().maxDepth;
    BDPTIntegrator balance(*scene, maxDepth, MisHeuristic::Balance);
    BDPTIntegrator powerOne(*scene, maxDepth, parseMisWeighting("power:1"));
    BDPTIntegrator cutoffZero(*scene, maxDepth, parseMisWeighting("cutoff:0"));
    const Subpaths& paths = balance.subpaths();
    auto sampler = createSampler("independent", 13, 1);
    ScratchBuffer scratch;
    PathStats stats;
    int compared = 0;
    for (int i = 0; i < 1500; ++i) {
        auto [camera, light, nc, nl] = tracePair(*scene, paths, *sampler, scratch, stats, i);
        for (int t = 2; t <= nc; ++t)
            for (int s = 2; s <= nl; ++s) {
                if (s + t - 2 > paths.maxDepth()) continue;
                auto c = balance.connect(light, camera, s, t, *sampler, stats, false);
                if (c.L.isBlack()) continue;
                FullPath fp = rebuild(paths, light, s, camera, t);
                for (int sp = 0; sp <= int(fp.y.size()); ++sp) {
                    if (!possible(balance, fp, sp)) continue;
                    const float b = weightOf(balance, fp, sp);
                    EXPECT_NEAR(weightOf(powerOne, fp, sp), b, 1e-5f) << "s' " << sp << " of s " << s << " t " << t;
                    EXPECT_NEAR(weightOf(cutoffZero, fp, sp), b, 1e-5f) << "s' " << sp << " of s " << s << " t " << t;
                    ++compared;
                }
            }
        scratch.reset();
    }
    std::printf("  %d strategy weights compared\n", compared);
    EXPECT_GE(compared, 1000);
}

// With a light path share below 1 a camera sample is a BDPT sample with that probability and
// a path tracer's otherwise (setLightPathShare). A path the path tracer samples too (one that
// BDPT's s' = 0 or s' = 1 can produce) keeps its contribution in the BDPT samples; one that
// only light subpaths reach (the point light seen in the mirror) counts 1 / share. The rule is
// checked against which strategies can produce each random path (possible(), above).
TEST(BdptMis, LightPathShareScalesOnlyThePathsThePathTracerMisses) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(kScene, ".", "<test>");
    auto scene = buildScene(desc);
    constexpr float kShare = 0.25f;
    BDPTIntegrator bdpt(*scene, scene->settings().maxDepth);
    bdpt.setLightPathShare(kShare);
    const Subpaths& paths = bdpt.subpaths();
    auto sampler = createSampler("independent", 23, 1);
    ScratchBuffer scratch;
    PathStats stats;
    int both = 0, lightOnly = 0;
    for (int i = 0; i < 4000; ++i) {
        auto [camera, light, nc, nl] = tracePair(*scene, paths, *sampler, scratch, stats, i);
        for (int t = 1; t <= nc; ++t)
            for (int s = 2; s <= nl; ++s) {
                if (s + t - 2 > paths.maxDepth()) continue;
                const FullPath fp = rebuild(paths, light, s, camera, t);
                if (!possible(bdpt, fp, s)) continue;
                const bool pathTracer = possible(bdpt, fp, 0) || possible(bdpt, fp, 1);
                EXPECT_FLOAT_EQ(bdpt.lightSubpathScale(light, s, t), pathTracer ? 1.0f : 1 / kShare)
                    << "s " << s << ", t " << t;
                (pathTracer ? both : lightOnly) += 1;
            }
        // t = 0 from the light itself: the camera ray finds an area light, never a point light.
        if (nl >= 1) EXPECT_FLOAT_EQ(bdpt.lightSubpathScale(light, 1, 0), light[0].isDeltaLight() ? 1 / kShare : 1.0f);
        scratch.reset();
    }
    std::printf("  %d paths the path tracer samples too, %d only light subpaths reach\n", both, lightOnly);
    EXPECT_GE(both, 1000);
    EXPECT_GE(lightOnly, 20);
    // At share 1 nothing is scaled.
    BDPTIntegrator whole(*scene, scene->settings().maxDepth);
    auto [camera, light, nc, nl] = tracePair(*scene, paths, *sampler, scratch, stats, 7);
    for (int s = 1; s <= nl; ++s) EXPECT_EQ(whole.lightSubpathScale(light, s, 1), 1.0f);
}

// Every strategy, including next-event (s = 1) and lens (t = 1) connections: the weight a
// connection computes from the densities its own BSDF and emission queries produced (and the
// running sums along its subpaths) equals
// the weight from densities evaluated afresh at the join (to the same 2e-3 as above). The light includes a point light,
// so delta light vertices take part.
TEST(BdptMis, ConnectionDensitiesMatchFreshOnes) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(kScene, ".", "<test>");
    auto scene = buildScene(desc);
    BDPTIntegrator bdpt(*scene, scene->settings().maxDepth, MisHeuristic::Power);
    bdpt.recomputeWeights(true);
    const Subpaths& paths = bdpt.subpaths();
    auto sampler = createSampler("independent", 9, 1);
    ScratchBuffer scratch;
    PathStats stats;
    int checked[3] = {0, 0, 0};  // s = 1, t = 1, both > 1
    for (int i = 0; i < 3000; ++i) {
        auto [camera, light, nc, nl] = tracePair(*scene, paths, *sampler, scratch, stats, i);
        const auto prefixes = bdpt.misPrefixes(light, nl, camera, nc, scratch);
        for (int t = 1; t <= nc; ++t)
            for (int s = 0; s <= nl; ++s) {
                if ((s == 1 && t == 1) || s + t - 2 > paths.maxDepth() || s + t < 2) continue;
                auto c = bdpt.connect(light, camera, s, t, *sampler, stats, true, &prefixes);
                if (c.L.isBlack()) continue;
                // The walks' stored densities use the sampled directions, the fresh ones the
                // directions between hit points (see above): skip vertices a few mm apart.
                bool close = false;
                for (int j = 1; j < t; ++j) close |= length(camera[j].p - camera[j - 1].p) < 0.05f;
                for (int j = 1; j < s; ++j) close |= length(light[j].p - light[j - 1].p) < 0.05f;
                if (close) continue;
                EXPECT_NEAR(c.weight, c.recomputedWeight, 2e-3f * std::max(1.0f, c.recomputedWeight))
                    << "s " << s << " t " << t;
                if (s == 1) ++checked[0];
                else if (t == 1) ++checked[1];
                else if (s > 1) ++checked[2];
            }
        scratch.reset();
    }
    std::printf("  connections checked: %d next-event, %d lens, %d inner\n", checked[0], checked[1], checked[2]);
    for (int k = 0; k < 3; ++k) EXPECT_GE(checked[k], 300);
}
