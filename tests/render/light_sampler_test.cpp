// The light samplers (lights/light_sampler.h): at many points of a scene with lights of every
// kind, the probabilities pmf() gives sum to one (bvh: less what its walk may lose) and match
// how often sample() chooses each light (chi-square), and sample() reports the probability
// pmf() gives; the bvh sampler never gives zero to a light that can reach the point; the
// scene's "lightsampler" is honoured; and the path tracer renders the same image with each
// sampler, with less noise by bvh where many small lights each matter only nearby.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>

#include "lights/bvh_light_sampler.h"
#include "lights/emission_choice.h"
#include "materials/stats.h"
#include "mc/rng.h"
#include "render_helpers.h"
#include "temp_images.h"

using namespace ps;
using namespace ps::test;

namespace {

const char* const kSamplers[] = {"uniform", "power", "bvh"};

// Lights of every kind spread over [-5, 5]^3, with powers over two orders of magnitude:
// one-sided quads (two triangles, so two lights each) facing every way, one of them emitting
// on the side its normals N choose against its winding, and one two-sided quad,
// spheres (one turned inside out: it lights only its inside), a one-sided disk, a cylinder,
// point lights, spot lights (one without falloff), a goniometric light, a projection light
// through a sheared frustum, a distant light and a uniform infinite light.
std::string manyLightsWorld(const std::string& slide) {
    std::ostringstream w;
    Rng rng(11);
    auto r = [&](float a, float b) { return a + (b - a) * rng.uniform(); };
    auto rgb = [&](float lo, float hi) {
        std::ostringstream c;
        c << "[ " << r(lo, hi) << " " << r(lo, hi) << " " << r(lo, hi) << " ]";
        return c.str();
    };
    auto place = [&] {
        w << "Translate " << r(-5, 5) << " " << r(-5, 5) << " " << r(-5, 5) << "\n"
          << "Rotate " << r(0, 360) << " " << r(0.1f, 1) << " " << r(-1, 1) << " " << r(-1, 1) << "\n";
    };
    for (int i = 0; i < 14; ++i) {
        w << "AttributeBegin\n";
        w << "AreaLightSource \"diffuse\" \"rgb L\" " << rgb(0.1f, 10) << (i == 12 ? " \"bool twosided\" true" : "") << "\n";
        place();
        w << "Scale " << r(0.2f, 1.5f) << " " << r(0.2f, 1.5f) << " 1\n"
          << "Shape \"trianglemesh\" \"point3 P\" [ -0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0 ]"
             " \"integer indices\" [ 0 1 2 0 2 3 ]"
          << (i == 13 ? " \"normal N\" [ 0 0 -1  0 0 -1  0 0 -1  0 0 -1 ]" : "") << "\nAttributeEnd\n";
    }
    for (int i = 0; i < 3; ++i) {
        w << "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" " << rgb(0.1f, 10) << "\n";
        place();
        if (i == 2) w << "ReverseOrientation\n";
        w << "Shape \"sphere\" \"float radius\" [ " << r(0.1f, 0.8f) << " ]\nAttributeEnd\n";
    }
    w << "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" " << rgb(0.1f, 10) << "\n";
    place();
    w << "Shape \"disk\" \"float radius\" [ 0.7 ]\nAttributeEnd\n";
    w << "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" " << rgb(0.1f, 10) << "\n";
    place();
    w << "Shape \"cylinder\" \"float radius\" [ 0.3 ] \"float zmin\" [ -0.5 ] \"float zmax\" [ 0.5 ]\nAttributeEnd\n";
    for (int i = 0; i < 3; ++i)
        w << "LightSource \"point\" \"rgb I\" " << rgb(0.5f, 20) << " \"point3 from\" [ " << r(-5, 5) << " " << r(-5, 5)
          << " " << r(-5, 5) << " ]\n";
    for (int i = 0; i < 3; ++i)
        w << "LightSource \"spot\" \"rgb I\" " << rgb(0.5f, 20) << " \"point3 from\" [ " << r(-5, 5) << " " << r(-5, 5)
          << " " << r(-5, 5) << " ] \"point3 to\" [ " << r(-5, 5) << " " << r(-5, 5) << " " << r(-5, 5)
          << " ] \"float coneangle\" [ " << 20 + 15 * i << " ] \"float conedeltaangle\" [ " << (i == 0 ? 0 : 10) << " ]\n";
    w << "AttributeBegin\n";
    place();
    w << "LightSource \"goniometric\" \"rgb I\" [ 3 3 3 ]\nAttributeEnd\n";
    w << "AttributeBegin\n";
    place();
    w << "Scale 1 1.6 0.8\nLightSource \"projection\" \"float fov\" [ 50 ] \"float scale\" [ 4 ] \"string filename\" [ \""
      << slide << "\" ]\nAttributeEnd\n";
    w << "LightSource \"distant\" \"rgb L\" [ 2 2 2 ] \"point3 from\" [ 1 3 2 ] \"point3 to\" [ 0 0 0 ]\n";
    w << "LightSource \"infinite\" \"rgb L\" [ 0.3 0.3 0.3 ]\n";
    return w.str();
}

std::unique_ptr<Scene> buildWorld(const std::string& world, const std::string& integrator = "") {
    setWarningsQuiet(true);
    return buildScene(parseSceneString(R"(
        LookAt 0 0 20  0 0 0  0 1 0
        Camera "perspective"
        Film "rgb" "integer xresolution" [ 4 ] "integer yresolution" [ 4 ]
    )" + integrator + "\nWorldBegin\n" + world, ".", "<test>"));
}

// That scene, and its lights in the scene's order. The projection light's slide has texels of
// different brightness, one of them black.
struct ManyLights {
    TempImages tmp{"light-sampler"};
    std::unique_ptr<Scene> scene;
    std::vector<const Light*> lights;
    ManyLights() {
        Image slide(3, 2);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 3; ++x) slide.set(x, y, x + y == 0 ? Spectrum() : Spectrum(1.0f + x, 0.5f + y, 1.0f));
        scene = buildWorld(manyLightsWorld(tmp.write("slide.pfm", slide)));
        for (const auto& l : scene->lights()) lights.push_back(l.get());
    }
};

// A receiving point in [-6, 6]^3 with a random unit normal; every fifth has none (a point
// not on a surface).
LightSampleContext randomPoint(Rng& rng, int k) {
    auto r = [&](float a, float b) { return a + (b - a) * rng.uniform(); };
    LightSampleContext ctx;
    ctx.p = Vec3(r(-6, 6), r(-6, 6), r(-6, 6));
    Vec3 n;
    do n = Vec3(r(-1, 1), r(-1, 1), r(-1, 1));
    while (!(lengthSquared(n) > 0.01f) || lengthSquared(n) > 1);
    ctx.ng = k % 5 == 4 ? Vec3() : normalize(n);
    return ctx;
}

constexpr int kPoints = 200;

}  // namespace

// The scene has every kind of light the samplers must handle.
TEST(LightSampler, TestSceneHasEveryKindOfLight) {
    ManyLights m;
    int kinds[4] = {0, 0, 0, 0}, bounded = 0;
    for (const Light* l : m.lights) {
        ++kinds[int(l->type())];
        bounded += l->bounds().has_value();
    }
    EXPECT_EQ(m.lights.size(), 28u + 3 + 2 + 3 + 3 + 1 + 1 + 2);
    EXPECT_EQ(kinds[int(LightType::Area)], 33);
    EXPECT_EQ(kinds[int(LightType::DeltaPosition)], 8);
    EXPECT_EQ(kinds[int(LightType::DeltaDirection)], 1);
    EXPECT_EQ(kinds[int(LightType::Infinite)], 1);
    EXPECT_EQ(bounded, 41);  // all but the distant and the infinite light
}

// At each of 200 points, for each sampler: the probabilities of all lights sum to one (for
// bvh: to one less the probability of choosing nothing, which happens where the tree's walk
// meets a node whose lights cannot reach the point, as in pbrt-v4); 4000 choices follow
// them (Pearson's chi-square, with "nothing" as one more cell); and each choice reports the
// probability pmf() gives its light. The chi-square is judged per point (Sidak-corrected over
// the 600 tests) and summed over the points of each sampler.
TEST(LightSampler, ChoicesFollowTheirProbabilities) {
    ManyLights m;
    const size_t n = m.lights.size();
    constexpr int kChoices = 4000;
    const double perTest = sidak(1e-3, 3 * kPoints);
    for (const char* name : kSamplers) {
        auto sampler = createLightSampler(name, m.lights);
        Rng rng(1234);
        double chi2Sum = 0, worstP = 1, deficitSum = 0, maxMismatch = 0;
        int dofSum = 0, pointsShort = 0;
        for (int k = 0; k < kPoints; ++k) {
            const LightSampleContext ctx = randomPoint(rng, k);
            std::vector<double> expected(n + 1), observed(n + 1, 0.0);
            double sum = 0;
            for (size_t i = 0; i < n; ++i) {
                float p = sampler->pmf(ctx, m.lights[i]);
                ASSERT_TRUE(p >= 0 && p <= 1) << name << " point " << k << " light " << i << ": pmf " << p;
                sum += p;
                expected[i] = p * kChoices;
            }
            ASSERT_LE(sum, 1 + 1e-5) << name << " point " << k;
            if (std::string(name) != "bvh") {
                EXPECT_NEAR(sum, 1, 1e-5) << name << " point " << k;
            }
            if (sum < 1 - 1e-5) {
                ++pointsShort;
                deficitSum += 1 - sum;
            }
            expected[n] = std::max(0.0, 1 - sum) * kChoices;
            for (int j = 0; j < kChoices; ++j) {
                SampledLight s = sampler->sample(ctx, rng.uniform());
                if (!s.light) {
                    observed[n] += 1;
                    continue;
                }
                ASSERT_GE(s.light->index, 0);
                observed[size_t(s.light->index)] += 1;
                float p = sampler->pmf(ctx, s.light);
                double mismatch = std::fabs(s.pmf - p) / p;
                maxMismatch = std::max(maxMismatch, mismatch);
                ASSERT_LE(mismatch, 1e-5) << name << " point " << k << " light " << s.light->index << ": sample says "
                                          << s.pmf << ", pmf " << p;
            }
            ChiSquareResult c = chiSquare(observed, expected);
            EXPECT_GT(c.pValue, perTest) << name << " point " << k << ": chi2 " << c.chi2 << " dof " << c.dof;
            chi2Sum += c.chi2;
            dofSum += c.dof;
            worstP = std::min(worstP, c.pValue);
        }
        const double pAll = chiSquarePValue(chi2Sum, dofSum);
        std::printf("%-7s chi2 %.0f over %d dof (p %.3f), worst point p %.2g; sum of pmf below 1 at %d of %d points "
                    "(mean deficit there %.3g); largest |sample pmf - pmf| / pmf %.2g\n",
                    name, chi2Sum, dofSum, pAll, worstP, pointsShort, kPoints,
                    pointsShort ? deficitSum / pointsShort : 0.0, maxMismatch);
        EXPECT_GT(pAll, 1e-3) << name;
    }
}

// The context-free choice (light subpaths): by power for power and bvh, uniform for uniform;
// sample(u) agrees with pmf(light).
TEST(LightSampler, ChoiceWithoutAPoint) {
    ManyLights m;
    double total = 0;
    for (const Light* l : m.lights) total += l->phi().luminance();
    for (const char* name : kSamplers) {
        auto sampler = createLightSampler(name, m.lights);
        double sum = 0;
        for (const Light* l : m.lights) {
            float p = sampler->pmf(l);
            sum += p;
            double want = std::string(name) == "uniform" ? 1.0 / m.lights.size() : l->phi().luminance() / total;
            EXPECT_NEAR(p, want, 1e-5 + 1e-4 * want) << name << " light " << l->index;
        }
        EXPECT_NEAR(sum, 1, 1e-5) << name;
        for (int j = 0; j < 64; ++j) {
            SampledLight s = sampler->sample((j + 0.5f) / 64);
            ASSERT_TRUE(s.light);
            EXPECT_EQ(s.pmf, sampler->pmf(s.light)) << name;
        }
    }
}

// Light subpaths' choice (lights/emission_choice.h): with the bvh sampler, the bounded lights'
// share of power is split between the tree's choice at the camera's position and power; every
// light keeps at least kEmissionPowerShare of its power share (so none that emits is left
// out), the lights at infinity keep theirs, and sampleLight agrees with lightPmf.
TEST(LightSampler, EmissionChoiceFollowsTheCamera) {
    ManyLights m;
    const Scene& scene = *m.scene;
    double total = 0, bounded = 0, treeTotal = 0;
    const LightSampleContext eye{scene.camera().position(), Vec3()};
    for (const Light* l : m.lights) {
        total += l->phi().luminance();
        if (l->bounds()) {
            bounded += l->phi().luminance();
            treeTotal += scene.lightSampler().pmf(eye, l);
        }
    }
    ASSERT_GT(treeTotal, 0);
    double sum = 0;
    int moved = 0;
    for (const Light* l : m.lights) {
        const double power = l->phi().luminance() / total, p = scene.lightPmf(l);
        sum += p;
        double want = power;
        if (l->bounds()) {
            want = ((1 - kEmissionPowerShare) * scene.lightSampler().pmf(eye, l) / treeTotal +
                    kEmissionPowerShare * l->phi().luminance() / bounded) * bounded / total;
            EXPECT_GE(p, 0.999 * kEmissionPowerShare * power) << "light " << l->index;
        }
        EXPECT_NEAR(p, want, 1e-5 + 1e-4 * want) << "light " << l->index;
        moved += std::fabs(p - power) > 0.2 * power;
    }
    EXPECT_NEAR(sum, 1, 1e-5);
    EXPECT_GT(moved, 5);  // the choice is not power's
    for (int j = 0; j < 64; ++j) {
        float pmf = 0;
        const Light* l = scene.sampleLight((j + 0.5f) / 64, &pmf);
        ASSERT_TRUE(l);
        EXPECT_EQ(pmf, scene.lightPmf(l));
    }
    // Other light samplers, and a tree of one leaf, leave it by power.
    auto power = buildWorld(manyLightsWorld(m.tmp.write("slide2.pfm", Image(1, 1))),
                            R"(Integrator "path" "string lightsampler" [ "power" ])");
    double totalPower = 0;
    for (const auto& l : power->lights()) totalPower += l->phi().luminance();
    for (const auto& l : power->lights())
        EXPECT_NEAR(power->lightPmf(l.get()), l->phi().luminance() / totalPower, 1e-6) << "light " << l->index;
}

// bvh gives a light zero probability only where it cannot reach the point: at 2000 points, a
// light reaches p if any of 16 x 16 samples of its incident light at p (occlusion aside)
// carries radiance.
// Zeros must occur too (behind one-sided quads, the disk, outside spot cones and the
// projector's frustum), or the bounds would be doing nothing.
TEST(LightSampler, BvhZeroOnlyWhereALightCannotReach) {
    ManyLights m;
    auto sampler = createLightSampler("bvh", m.lights);
    Rng rng(99);
    int zeros = 0, reachable = 0, pairs = 0;
    for (int k = 0; k < 10 * kPoints; ++k) {
        const LightSampleContext ctx = randomPoint(rng, k);
        for (const Light* l : m.lights) {
            bool reaches = false;
            for (int a = 0; a < 16 && !reaches; ++a)
                for (int b = 0; b < 16 && !reaches; ++b) {
                    auto ls = l->sampleLi(ctx, Vec2((a + 0.5f) / 16, (b + 0.5f) / 16));
                    reaches = ls && !ls->L.isBlack() && ls->pdf > 0;
                }
            float p = sampler->pmf(ctx, l);
            ++pairs;
            reachable += reaches;
            if (p == 0) {
                ++zeros;
                EXPECT_FALSE(reaches) << "point " << k << " (" << ctx.p.x << ", " << ctx.p.y << ", " << ctx.p.z
                                      << "): light " << l->index << " reaches it but has probability 0";
            }
        }
    }
    std::printf("bvh: %d of %d light-point pairs have probability 0; %d of the other %d cannot reach the point either\n",
                zeros, pairs, pairs - reachable - zeros, pairs - zeros);
    EXPECT_GT(zeros, pairs / 20);
}

// A point light facing nothing but the back of a one-sided quad: the quad gets nothing, the
// point light everything, and with a sky, the sky takes the place of an unlit tree.
TEST(LightSampler, BvhShareOfLightsAtInfinity) {
    const std::string quad = R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Shape "trianglemesh" "point3 P" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] "integer indices" [ 0 1 2 0 2 3 ]
        AttributeEnd
    )";
    auto scene = buildWorld(quad + "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n");
    std::vector<const Light*> lights;
    for (const auto& l : scene->lights()) lights.push_back(l.get());
    ASSERT_EQ(lights.size(), 3u);  // two triangles and the sky
    BVHLightSampler bvh(lights);
    EXPECT_EQ(bvh.nodeCount(), 1);  // the two triangles have the same bounds: one leaf
    // In front of the quad (+z): the sky has its pbrt-v4 share 1/2, the triangles the rest.
    LightSampleContext front{{0.2f, 0.1f, 3}, {0, 0, -1}};
    EXPECT_FLOAT_EQ(bvh.pmf(front, lights[2]), 0.5f);
    EXPECT_NEAR(bvh.pmf(front, lights[0]) + bvh.pmf(front, lights[1]), 0.5f, 1e-6f);
    EXPECT_GT(bvh.pmf(front, lights[0]), 0.0f);
    // Far behind it: only the sky can light the point, and it is always chosen.
    LightSampleContext behind{{0, 0, -30}, {0, 0, 1}};
    EXPECT_EQ(bvh.pmf(behind, lights[0]), 0.0f);
    EXPECT_EQ(bvh.pmf(behind, lights[1]), 0.0f);
    EXPECT_EQ(bvh.pmf(behind, lights[2]), 1.0f);
    for (float u : {0.0f, 0.3f, 0.7f, 0.999f}) EXPECT_EQ(bvh.sample(behind, u).light, lights[2]);
}

// Lights with the same bounds but for power share a leaf and are chosen by power within it,
// at every point as the tree would choose them; a light elsewhere still has a node of its own.
TEST(LightSampler, BvhLeafOfLightsWithTheSameBounds) {
    const std::string world = R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Shape "trianglemesh" "point3 P" [ -1 -1 0  1 -1 0  1 1 0  -1 1 0 ] "integer indices" [ 0 1 2 0 2 3 ]
        AttributeEnd
        LightSource "point" "point3 from" [ 0 0 5 ] "rgb I" [ 1 1 1 ]
        LightSource "point" "point3 from" [ 0 0 5 ] "rgb I" [ 3 3 3 ]
        LightSource "point" "point3 from" [ 9 0 5 ] "rgb I" [ 1 1 1 ]
    )";
    auto scene = buildWorld(world);
    std::vector<const Light*> lights;
    for (const auto& l : scene->lights()) lights.push_back(l.get());
    ASSERT_EQ(lights.size(), 5u);
    // Which is which, by bounds and power.
    std::vector<const Light*> quad, atOnePoint;
    for (const Light* l : lights) {
        const LightBounds b = *l->bounds();
        if (b.bounds.lo.x != b.bounds.hi.x) quad.push_back(l);
        else if (b.bounds.lo.x == 0) atOnePoint.push_back(l);
    }
    ASSERT_EQ(quad.size(), 2u);
    ASSERT_EQ(atOnePoint.size(), 2u);
    if (atOnePoint[0]->bounds()->phi > atOnePoint[1]->bounds()->phi) std::swap(atOnePoint[0], atOnePoint[1]);
    BVHLightSampler bvh(lights);
    EXPECT_EQ(bvh.nodeCount(), 5);  // three leaves: the quad, the two lights at one point, the last
    for (Vec3 p : {Vec3(0.2f, 0.1f, 3), Vec3(5, -2, 1), Vec3(-3, 4, 8)}) {
        LightSampleContext ctx{p, {0, 0, 0}};
        EXPECT_FLOAT_EQ(bvh.pmf(ctx, quad[0]), bvh.pmf(ctx, quad[1]));
        EXPECT_GT(bvh.pmf(ctx, atOnePoint[0]), 0.0f);
        EXPECT_NEAR(bvh.pmf(ctx, atOnePoint[1]), 3 * bvh.pmf(ctx, atOnePoint[0]), 1e-6f);
        float sum = 0;
        for (const Light* l : lights) sum += bvh.pmf(ctx, l);
        EXPECT_NEAR(sum, 1.0f, 1e-5f);
        // Within a leaf, u chooses by power, and sample() reports the pmf that pmf() gives.
        for (int i = 0; i < 64; ++i) {
            SampledLight sl = bvh.sample(ctx, (float(i) + 0.5f) / 64);
            ASSERT_NE(sl.light, nullptr);
            EXPECT_EQ(sl.pmf, bvh.pmf(ctx, sl.light));
        }
    }
}

// "lightsampler" chooses the scene's sampler; an unknown name is an error at the parameter.
TEST(LightSampler, SceneHonoursLightsampler) {
    const std::string world = "LightSource \"point\" \"rgb I\" [ 1 1 1 ]\n";
    EXPECT_NE(dynamic_cast<const BVHLightSampler*>(&buildWorld(world)->lightSampler()), nullptr);
    EXPECT_NE(dynamic_cast<const PowerLightSampler*>(
                  &buildWorld(world, R"(Integrator "path" "string lightsampler" [ "power" ])")->lightSampler()),
              nullptr);
    EXPECT_NE(dynamic_cast<const UniformLightSampler*>(
                  &buildWorld(world, R"(Integrator "path" "string lightsampler" [ "uniform" ])")->lightSampler()),
              nullptr);
    try {
        buildWorld(world, "Integrator \"path\"\n  \"string lightsampler\" [ \"nearest\" ]");
        ADD_FAILURE() << "no error for an unknown lightsampler";
    } catch (const InputError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("<test>:6"), std::string::npos) << msg;  // the parameter's line
        EXPECT_NE(msg.find("\"nearest\""), std::string::npos) << msg;
    }
}

namespace {

// The camera, film, sampler and Integrator lines of the scenes below.
std::string header(const std::string& lookAt, int fov, int w, int h, int maxDepth, const std::string& lightsampler) {
    std::ostringstream s;
    s << "LookAt " << lookAt << "\nCamera \"perspective\" \"float fov\" [ " << fov << " ]\n"
      << "Film \"rgb\" \"integer xresolution\" [ " << w << " ] \"integer yresolution\" [ " << h << " ]\n"
      << "PixelFilter \"box\"\nSampler \"independent\"\n"
      << "Integrator \"path\" \"integer maxdepth\" [ " << maxDepth << " ] \"string lightsampler\" [ \"" << lightsampler
      << "\" ]\nWorldBegin\n";
    return s.str();
}

// A room (floor, back wall) lit by 24 lights of several kinds at different heights, a
// distant light and a dim sky; the camera sees floor, wall and some of the lights.
std::string roomScene(const std::string& lightsampler) {
    std::ostringstream s;
    s << header("0 3 9  0 1 0  0 1 0", 50, 24, 16, 3, lightsampler) << R"(
        LightSource "distant" "rgb L" [ 0.5 0.5 0.5 ] "point3 from" [ 1 4 3 ] "point3 to" [ 0 0 0 ]
        LightSource "infinite" "rgb L" [ 0.05 0.05 0.05 ]
        Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
        Shape "trianglemesh" "point3 P" [ -6 0 -4  6 0 -4  6 0 6  -6 0 6 ] "integer indices" [ 0 2 1 0 3 2 ]
        Shape "trianglemesh" "point3 P" [ -6 0 -4  6 0 -4  6 6 -4  -6 6 -4 ] "integer indices" [ 0 1 2 0 2 3 ]
    )";
    Rng rng(5);
    auto r = [&](float a, float b) { return a + (b - a) * rng.uniform(); };
    for (int i = 0; i < 24; ++i) {
        float x = r(-5, 5), y = r(0.5f, 4), z = r(-3.5f, 4);
        float L = r(1, 12);
        switch (i % 4) {
        case 0:
            s << "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ " << L << " " << L << " " << 0.8f * L
              << " ]\nTranslate " << x << " " << y << " " << z << "\nRotate " << r(0, 360) << " 1 0.3 0.2\n"
              << "Shape \"trianglemesh\" \"point3 P\" [ -0.2 -0.2 0  0.2 -0.2 0  0.2 0.2 0  -0.2 0.2 0 ]"
                 " \"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n";
            break;
        case 1:
            s << "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ " << L << " " << L << " " << L
              << " ]\nTranslate " << x << " " << y << " " << z << "\nShape \"sphere\" \"float radius\" [ 0.15 ]\nAttributeEnd\n";
            break;
        case 2:
            s << "LightSource \"point\" \"rgb I\" [ " << 0.3f * L << " " << 0.3f * L << " " << 0.3f * L
              << " ] \"point3 from\" [ " << x << " " << y << " " << z << " ]\n";
            break;
        default:
            s << "LightSource \"spot\" \"rgb I\" [ " << L << " " << L << " " << L << " ] \"point3 from\" [ " << x << " " << y
              << " " << z << " ] \"point3 to\" [ " << x + r(-2, 2) << " 0 " << z + r(-2, 2) << " ] \"float coneangle\" [ 35 ]\n";
        }
    }
    return s.str();
}

// A corridor 80 long: floor and ceiling, and 60 small one-sided lights along the ceiling,
// facing down; the camera looks down at the floor (no light in view, whose edges in the
// pixels would add the same noise under either sampler). Each floor point is lit mostly by
// the few lights above it.
std::string corridorScene(const std::string& lightsampler) {
    std::ostringstream s;
    s << header("0 1.8 0  0 0 -3  0 1 0", 40, 24, 16, 1, lightsampler) << R"(
        Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
        Shape "trianglemesh" "point3 P" [ -1 0 2  1 0 2  1 0 -80  -1 0 -80 ] "integer indices" [ 0 1 2 0 2 3 ]
        Shape "trianglemesh" "point3 P" [ -1 2.01 2  1 2.01 2  1 2.01 -80  -1 2.01 -80 ] "integer indices" [ 0 2 1 0 3 2 ]
    )";
    for (int i = 0; i < 60; ++i) {
        float z = 1 - 1.35f * i;
        s << "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 8 8 8 ]\nTranslate 0 2 " << z << "\n"
          << "Shape \"trianglemesh\" \"point3 P\" [ -0.1 0 -0.1  0.1 0 -0.1  0.1 0 0.1  -0.1 0 0.1 ]"
             " \"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n";
    }
    return s.str();
}

// Direct light only, on a floor under eight big one-sided quads of different heights and
// radiances and a sky: BSDF samples often hit the lights, so the MIS weights of those hits
// (the light sampler's probability at the point the path left) carry much of the image, and
// a weight evaluated elsewhere, or by another sampler, shows as a bias of several percent.
// The camera, below the lights, sees only the floor.
std::string misScene(const std::string& lightsampler) {
    std::ostringstream s;
    s << header("0 0.4 0  0 0 0  0 0 1", 90, 16, 16, 1, lightsampler) << R"(
        LightSource "infinite" "rgb L" [ 0.4 0.4 0.4 ]
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "trianglemesh" "point3 P" [ -5 0 -5  5 0 -5  5 0 5  -5 0 5 ] "integer indices" [ 0 1 2 0 2 3 ]
    )";
    const float xs[] = {-1, 1, -1, 1, 0, 0, -1.6f, 1.6f}, zs[] = {-1, -1, 1, 1, -1.6f, 1.6f, 0, 0};
    for (int i = 0; i < 8; ++i) {
        float h = 0.6f + 0.15f * i, L = 1 + 1.3f * float((i * 5) % 8);
        s << "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ " << L << " " << L << " " << L << " ]\nTranslate "
          << xs[i] << " " << h << " " << zs[i] << "\n"
          << "Shape \"trianglemesh\" \"point3 P\" [ -0.5 0 -0.5  0.5 0 -0.5  0.5 0 0.5  -0.5 0 0.5 ]"
             " \"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n";
    }
    return s.str();
}

struct ImageMoments {
    double mean = 0, stdErr = 0;  // of the image's mean luminance, across renders
    double pixelVariance = 0;     // mean over pixels of the luminance's variance across renders
};

ImageMoments renderMoments(const std::string& scene, int spp, int renders) {
    std::vector<std::vector<double>> pixels;
    std::vector<double> means;
    for (int k = 0; k < renders; ++k) {
        RenderResult r = renderString(scene, spp, 300 + uint64_t(k));
        std::vector<double> y;
        for (int py = 0; py < r.image.height; ++py)
            for (int px = 0; px < r.image.width; ++px) {
                Spectrum c = r.image.get(px, py);
                y.push_back(0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b);
            }
        double m = 0;
        for (double v : y) m += v;
        means.push_back(m / double(y.size()));
        pixels.push_back(std::move(y));
    }
    ImageMoments out;
    for (double m : means) out.mean += m / renders;
    double v = 0;
    for (double m : means) v += (m - out.mean) * (m - out.mean);
    out.stdErr = std::sqrt(v / (renders - 1) / renders);
    const size_t nPix = pixels[0].size();
    for (size_t i = 0; i < nPix; ++i) {
        double pm = 0, pv = 0;
        for (int k = 0; k < renders; ++k) pm += pixels[size_t(k)][i] / renders;
        for (int k = 0; k < renders; ++k) pv += (pixels[size_t(k)][i] - pm) * (pixels[size_t(k)][i] - pm);
        out.pixelVariance += pv / (renders - 1) / double(nPix);
    }
    return out;
}

// Renders `scene` under each sampler and expects the image means to agree within 4 sigma
// (sigma from `renders` renders of `spp` samples per pixel with independent seeds).
void expectSameImage(const char* what, std::string (*scene)(const std::string&), int spp, int renders) {
    ImageMoments m[3];
    for (int i = 0; i < 3; ++i) {
        m[i] = renderMoments(scene(kSamplers[i]), spp, renders);
        std::printf("%s, %-7s: mean %.5f +- %.5f, pixel variance %.4g\n", what, kSamplers[i], m[i].mean, m[i].stdErr,
                    m[i].pixelVariance);
    }
    for (int i = 0; i < 2; ++i)
        EXPECT_LT(std::fabs(m[i].mean - m[2].mean), 4 * std::hypot(m[i].stdErr, m[2].stdErr))
            << what << ": " << kSamplers[i] << " against bvh";
}

}  // namespace

// The path tracer gives the same image whichever sampler chooses its lights (each is an
// unbiased choice with its MIS weights evaluated at the point that chose).
TEST(LightSamplerRender, SamplersAgreeOnTheImage) { expectSameImage("room", roomScene, 64, 8); }
TEST(LightSamplerRender, SamplersAgreeWhereMisWeightsMatter) { expectSameImage("mis", misScene, 64, 8); }

// In the corridor, choosing by power (here: uniformly, all lights being alike) mostly picks
// lights far from the point; bvh picks the near ones, and its pixels vary much less (by
// over 200 times here; without the distance in its estimate, 12 times).
TEST(LightSamplerRender, BvhHasLessVarianceInACorridor) {
    ImageMoments bvh = renderMoments(corridorScene("bvh"), 4, 6);
    ImageMoments power = renderMoments(corridorScene("power"), 4, 6);
    std::printf("corridor: bvh mean %.5f +- %.5f, pixel variance %.4g; power mean %.5f +- %.5f, pixel variance %.4g "
                "(ratio %.2f)\n",
                bvh.mean, bvh.stdErr, bvh.pixelVariance, power.mean, power.stdErr, power.pixelVariance,
                power.pixelVariance / bvh.pixelVariance);
    EXPECT_LT(std::fabs(bvh.mean - power.mean), 4 * std::hypot(bvh.stdErr, power.stdErr));
    EXPECT_LT(bvh.pixelVariance, power.pixelVariance / 30);
}
