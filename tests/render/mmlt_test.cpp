// Multiplexed MLT's own machinery (transport/mlt/mmlt.*, strategy_choice.*): the two-level
// strategy choice, the bootstrap sample that stands for every strategy of its depth (a
// chain started from one of its states must find the same target value on its own), and
// the choice learned by the pilot. The images themselves are tested with pssmlt's in
// metropolis_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "mlt_scenes.h"
#include "render_helpers.h"
#include "transport/mlt/mmlt.h"
#include "transport/mlt/strategy_choice.h"

using namespace ps;
using namespace ps::test;

// Probabilities are the weights normalised; inversion over a fine grid of (u1, u2) chooses
// each strategy that often; a placed pair of values chooses its strategy, the tiniest one
// included.
TEST(StrategyChoice, ProbabilitiesSamplingAndPlacement) {
    const std::vector<float> w = {1, 3, 0.5f, 0.5f, 2, 1e-6f, 4};
    const StrategyChoice c(w, {0, 2, 5});
    double total = 0;
    for (float x : w) total += x;
    double sum = 0;
    for (int k = 0; k < c.size(); ++k) {
        EXPECT_NEAR(c.pmf(k), w[size_t(k)] / total, 1e-6 * (1 + w[size_t(k)] / total)) << k;
        sum += c.pmf(k);
    }
    EXPECT_NEAR(sum, 1.0, 1e-6);
    EXPECT_EQ(c.groupOf(1), 0);
    EXPECT_EQ(c.groupOf(4), 1);
    EXPECT_EQ(c.groupOf(6), 2);
    const int n = 1000;
    std::vector<double> count(w.size(), 0.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            float pmf = 0;
            const int k = c.sample((float(i) + 0.5f) / n, (float(j) + 0.5f) / n, &pmf);
            EXPECT_EQ(pmf, c.pmf(k));
            count[size_t(k)] += 1.0 / (double(n) * n);
        }
    for (int k = 0; k < c.size(); ++k) EXPECT_NEAR(count[size_t(k)], c.pmf(k), 2.0 / n) << k;
    for (int k = 0; k < c.size(); ++k)
        for (double u : {0.0, 0.3, 0.5, 0.999999}) {
            double v1 = -1, v2 = -1;
            c.place(k, u, 1 - u, v1, v2);
            EXPECT_EQ(c.sample(float(v1), float(v2), nullptr), k) << k << " at " << u;
        }
}

namespace {

// A corner of a room with a glass sphere and a small emitter facing down, just outside the
// view: every kind of strategy (s = 0, 1, t = 1, inner connections) carries light at some
// depth, specular vertices included.
const char* kGlassBox = R"(
    LookAt 0 0.5 1.9  0 0.5 0  0 1 0
    Camera "perspective" "float fov" [ 30 ]
    Film "rgb" "integer xresolution" [ 12 ] "integer yresolution" [ 12 ]
    PixelFilter "box"
    Integrator "mmlt" "integer maxdepth" [ 4 ] "integer chains" [ 16 ] "integer bootstrapsamples" [ 4000 ]
    WorldBegin
    Material "diffuse" "rgb reflectance" [ 0.6 0.5 0.4 ]
    Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ]
        "point3 P" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ]
    Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ]
        "point3 P" [ -1 0 -1  -1 1.2 -1  1 1.2 -1  1 0 -1 ]
    AttributeBegin
      Material "dielectric" "float eta" [ 1.5 ]
      Translate 0.1 0.35 0
      Shape "sphere" "float radius" [ 0.3 ]
    AttributeEnd
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 20 20 20 ]
      Translate -0.3 1.1 0.2
      Rotate 90 1 0 0
      Shape "disk" "float radius" [ 0.1 ]
    AttributeEnd
)";

std::unique_ptr<Scene> parse(const std::string& text) {
    setWarningsQuiet(true);
    return buildScene(parseSceneString(text, ".", "<test>"));
}

// The same box without the glass sphere: each depth's share is then smooth enough that a
// small pilot estimates it well.
std::string diffuseBox() {
    std::string text = kGlassBox;
    const size_t a = text.find("    AttributeBegin\n      Material \"dielectric\"");
    const size_t b = text.find("AttributeEnd", a) + std::string("AttributeEnd\n").size();
    return text.erase(a, b - a);
}

}  // namespace

// A bootstrap sample evaluates every strategy of its depth from subpaths just long enough
// for it; each state it reports, placed as a chain's state, evaluates (one strategy's own,
// shorter subpaths) to the same target value, and every strategy it does not report
// evaluates to zero. This is what lets the chains start from the bootstrap's states in
// proportion to their weights without start-up bias.
namespace {
void expectEachStateIsItsStrategyAlone(const std::string& text) {
    auto scene = parse(text);
    MMLTIntegrator mmlt(*scene, 4);
    const StrategyChoice choice = mmlt.defaultChoice().withWeights([&] {
        std::vector<float> w(size_t(mmlt.defaultChoice().size()));
        for (size_t k = 0; k < w.size(); ++k) w[k] = 1.0f + float(k % 3);  // not the default
        return w;
    }());
    PrimarySampleParams pss;
    pss.streamCount = mmlt.streamCount();
    ChainEvaluator ev;
    ChainState x;
    std::vector<BootstrapState> found;
    std::set<std::pair<int, int>> kinds;  // (s, t) that carried light
    int states = 0, zeros = 0;
    const int depths = mmlt.maxDepth() + 1;
    for (int64_t i = 0; i < 3000; ++i) {
        PrimarySampleSampler sampler(1000 + uint64_t(i), pss);
        sampler.startIteration();
        mmlt.bootstrapSample(sampler, int(i % depths), 1.0, choice, ev, found);
        std::set<int> reported;
        for (const BootstrapState& st : found) {
            sampler.restartStreams();
            mmlt.chooseStrategy(sampler, st.strategy, choice, 0.25, 0.75);
            mmlt.evaluate(sampler, choice, ev, x);
            ASSERT_EQ(x.strategy, st.strategy);
            EXPECT_NEAR(x.f, st.f, 1e-5 * st.f) << "sample " << i << ", strategy " << st.strategy;
            const auto [d, s] = mmlt.strategies()[size_t(st.strategy)];
            EXPECT_EQ(d, int(i % depths));
            kinds.insert({s, d + 2 - s});
            reported.insert(st.strategy);
            ++states;
        }
        // The strategies of this depth that the sample did not report carry nothing.
        for (int k = 0; k < choice.size(); ++k) {
            if (mmlt.strategies()[size_t(k)].first != int(i % depths) || reported.count(k)) continue;
            sampler.restartStreams();
            mmlt.chooseStrategy(sampler, k, choice, 0.5, 0.5);
            mmlt.evaluate(sampler, choice, ev, x);
            EXPECT_EQ(x.f, 0.0) << "sample " << i << ", strategy " << k << " was not reported";
            ++zeros;
        }
    }
    std::printf("[ mmlt     ] %d bootstrap states replayed alone, %d unreported strategies evaluate to 0, %zu (s, t) "
                "kinds carried light\n",
                states, zeros, kinds.size());
    EXPECT_GT(states, 500);
    // s = 0, s = 1, t = 1 and inner connections at several depths.
    EXPECT_GE(kinds.size(), size_t(10));
}
}  // namespace

TEST(MMLTBootstrap, EachStateIsItsStrategyAlone) { expectEachStateIsItsStrategyAlone(kGlassBox); }

// The same with the camera and the lights in fog: medium vertices, their free flights and
// every connection's transmittance draw their numbers per walk and per strategy
// (MediaSample), so a strategy evaluated alone tracks what it did in the whole sample.
TEST(MMLTBootstrap, EachStateIsItsStrategyAloneInFog) {
    expectEachStateIsItsStrategyAlone(std::string(R"(MakeNamedMedium "fog" "string type" "homogeneous"
        "rgb sigma_a" [ 0.2 0.1 0.3 ] "rgb sigma_s" [ 0.9 0.5 0.2 ] "float g" [ 0.4 ]
    MediumInterface "" "fog"
)") + kGlassBox);
}

// The pilot learns how often to choose each depth: close to each depth's share of the
// image (as the chains measured it), mixed with a quarter of the default (each depth
// equally); the pilot's 1600 samples per depth leave it a few percent off (with 400, and a
// quarter of the mutations, 3 of 30 seeds were more than 10% off, in either colour mode).
// Without a pilot the choice is the default.
TEST(MMLTChoice, LearnedFromThePilotAsEachDepthsShare) {
    ASSERT_EQ(diffuseBox().find("dielectric"), std::string::npos);
    RenderResult learned = renderString(withBootstrap(diffuseBox(), 16000), 1024, 3, 0, "mmlt");
    const MetropolisStats& ms = learned.metropolis;
    const int depths = int(ms.depths.size());
    // A tenth of the bootstrap (the default), each depth equally; the rest split by depth.
    EXPECT_EQ(ms.pilotSamples, 1600 * depths);
    EXPECT_NEAR(double(ms.bootstrapSamples), 14400.0 * depths, depths);
    double sum = 0;
    for (int d = 0; d < depths; ++d) {
        const double expected = 0.75 * ms.depths[size_t(d)].share + 0.25 / depths;
        std::printf("[ mmlt     ] depth %d: share %.4f, chosen %.4f (expected %.4f)\n", d, ms.depths[size_t(d)].share,
                    ms.depths[size_t(d)].chosen, expected);
        EXPECT_NEAR(ms.depths[size_t(d)].chosen, expected, 0.1 * expected + 0.002) << "depth " << d;
        sum += ms.depths[size_t(d)].chosen;
    }
    EXPECT_NEAR(sum, 1.0, 1e-5);

    auto scene = parse(kGlassBox);
    scene->settings().mltStrategyPilot = 0;
    auto integ = createIntegrator("mmlt", *scene);
    RenderOptions o;
    o.spp = 16;
    o.progress = false;
    const MetropolisStats uniform = render(*scene, *integ, o).metropolis;
    EXPECT_EQ(uniform.pilotSamples, 0);
    EXPECT_EQ(uniform.bootstrapSamples, 4000 * depths);
    for (int d = 0; d < depths; ++d) EXPECT_NEAR(uniform.depths[size_t(d)].chosen, 1.0 / depths, 1e-6) << d;
}
