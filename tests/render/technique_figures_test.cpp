// The figures per technique (--stats, transport/technique_tally.h) and the variance from
// independent scramblings (transport/scrambled_sets.h): the shares sum to one and the
// techniques' means to the image's; each technique's reported variance agrees with the
// spread of its mean over independent renders; and on a smooth integrand the scramblings'
// variance of a QMC render is well below s^2 / n, which for independent samples it matches.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "many_lights_scene.h"
#include "render_helpers.h"
#include "transport/scrambled_sets.h"

using namespace ps;
using namespace ps::test;

namespace {

// One scene built once (RGB), rendered with several seeds.
struct SceneRenders {
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Integrator> integrator;
    SceneRenders(const std::string& text, const std::string& name) {
        setWarningsQuiet(true);
        SceneDescription desc = parseSceneString(text, ".", "<test>");
        scene = buildScene(desc, false);
        scene->settings().integrator = name;
        integrator = createIntegrator(name, *scene);
    }
    // With the technique figures; `sampler`'s scramblings as --stats chooses them.
    RenderResult run(const std::string& sampler, int spp, uint64_t seed, int threads = 0) const {
        RenderOptions opts;
        opts.spp = spp;
        opts.seed = seed;
        opts.threads = threads;
        opts.sampler = sampler;
        opts.progress = false;
        opts.techniqueFigures = true;
        opts.batches = batchCount(spp);
        opts.scramblings = scramblingCount(sampler, spp);
        return render(*scene, *integrator, opts);
    }
};

std::string smallManyLights() {
    std::string s = manyLightsScene();
    const std::string from = "\"integer xresolution\" [ 24 ] \"integer yresolution\" [ 24 ]";
    s.replace(s.find(from), from.size(), "\"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]");
    return s;
}

// The shares sum to one and the techniques' means to the image's mean luminance (the camera
// techniques through the pixels' means, the splatted ones through the film's normalisation;
// with a box filter, whose weights are all one and whose splats land in one pixel, exactly).
TEST(TechniqueFigures, SharesSumToOneAndMeansToTheImage) {
    std::string scene = manyLightsScene();
    scene.insert(scene.find("Sampler"), "PixelFilter \"box\"\n");
    for (const char* name : {"path", "bdpt"}) {
        SCOPED_TRACE(name);
        const SceneRenders s(scene, name);
        const RenderResult r = s.run("sobol", 16, 3);
        ASSERT_EQ(r.techniqueFigures.size(), r.techniques.size() + 1);
        double share = 0, mean = 0;
        for (size_t k = 0; k < r.techniques.size(); ++k) {
            share += r.techniqueFigures[k].share;
            mean += r.techniqueFigures[k].mean;
        }
        const double image = luminanceMean(r.image);
        std::printf("%s: shares sum to 1 %+.2e, techniques' means %.6f, image %.6f\n", name, share - 1, mean, image);
        EXPECT_NEAR(share, 1.0, 1e-12);
        EXPECT_NEAR(r.techniqueFigures.back().share, 1.0, 1e-12);
        EXPECT_NEAR(mean, image, 1e-6 * image);
    }
}

// Each technique's reported variance, averaged over R renders, against the variance of its
// mean over those R independent renders. The tolerance is the comparison's own sampling
// error: the observed variance's relative error from the means' kurtosis, the reported one's
// from its spread over the renders.
void expectVariancesAgree(const SceneRenders& s, const std::string& sampler, int spp, int renders) {
    const size_t n = s.integrator->techniques().size() + 1;
    std::vector<std::vector<double>> means(n), reported(n);
    for (int i = 0; i < renders; ++i) {
        const RenderResult r = s.run(sampler, spp, 1000 + uint64_t(i), 1);
        for (size_t k = 0; k < n; ++k) {
            means[k].push_back(r.techniqueFigures[k].mean);
            reported[k].push_back(r.techniqueFigures[k].variance);
        }
    }
    const double R = renders;
    int compared = 0;
    for (size_t k = 0; k < n; ++k) {
        double m = 0, v = 0, m4 = 0, rep = 0, rep2 = 0;
        for (int i = 0; i < renders; ++i) {
            m += means[k][size_t(i)] / R;
            rep += reported[k][size_t(i)] / R;
            rep2 += reported[k][size_t(i)] * reported[k][size_t(i)] / R;
        }
        for (int i = 0; i < renders; ++i) {
            const double d = means[k][size_t(i)] - m;
            v += d * d / (R - 1);
            m4 += d * d * d * d / R;
        }
        if (!(v > 0) || !(rep > 0)) continue;
        const double kurtosis = m4 / (v * v);
        const double relObserved2 = std::max(2 / (R - 1), (kurtosis - (R - 3) / (R - 1)) / R);
        const double relReported2 = std::max(0.0, rep2 - rep * rep) / (R - 1) / (rep * rep);
        const double sigma = std::sqrt(relObserved2 + relReported2);
        const std::string name = k + 1 < n ? s.integrator->techniques()[k].name : "image";
        std::printf("%s %-6s: reported %.4g, observed %.4g, ratio %.3f +- %.3f (%+.2f sigma)\n", sampler.c_str(),
                    name.c_str(), rep, v, rep / v, sigma, (rep / v - 1) / sigma);
        EXPECT_LT(std::fabs(rep / v - 1), 4 * sigma) << name;
        ++compared;
        if (k + 1 == n) {
            EXPECT_LT(4 * sigma, 0.6) << "the test must resolve a factor-2 error in the image's variance";
        }
    }
    EXPECT_GE(compared, 3);
}

TEST(TechniqueFigures, PathVarianceAgreesWithIndependentRenders) {
    const SceneRenders s(smallManyLights(), "path");
    expectVariancesAgree(s, "independent", 16, 160);  // 4 batches of independent samples
    expectVariancesAgree(s, "sobol", 16, 160);        // 4 scramblings
}

TEST(TechniqueFigures, BdptVarianceAgreesWithIndependentRenders) {
    const SceneRenders s(smallManyLights(), "bdpt");
    expectVariancesAgree(s, "sobol", 16, 160);
}

// A diffuse floor under a large rectangular light, direct light only: each pixel's integrand
// (film position, point on the light) is smooth, where randomised QMC converges much faster
// than independent samples. Its scramblings' variance falls well below s^2 / n; for
// independent samples, split into sets the same way, the two agree.
TEST(TechniqueFigures, ScramblingVarianceBelowSampleVarianceOnASmoothIntegrand) {
    const std::string scene = R"(
        LookAt 0 3 -3  0 0 0  0 1 0
        Camera "perspective" "float fov" [ 40 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 1 ]
        WorldBegin
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
        Shape "trianglemesh" "point3 P" [ -5 0 -5  5 0 -5  5 0 5  -5 0 5 ] "integer indices" [ 0 1 2 0 2 3 ]
        AttributeBegin
        AreaLightSource "diffuse" "rgb L" [ 2 2 2 ]
        Translate 0 2 0
        Shape "trianglemesh" "point3 P" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] "integer indices" [ 0 3 2 0 2 1 ]
        AttributeEnd
    )";
    const SceneRenders s(scene, "path");
    auto ratio = [&](const std::string& sampler) {
        RenderOptions plain;
        plain.spp = 64;
        plain.seed = 5;
        plain.sampler = sampler;
        plain.progress = false;
        const double sampleVariance = render(*s.scene, *s.integrator, plain).error.meanVariance;  // s^2 / n
        RenderOptions sets = plain;
        sets.scramblings = 8;
        const RenderResult r = render(*s.scene, *s.integrator, sets);
        EXPECT_EQ(r.scramblings, 8);
        std::printf("%s: scramblings' variance %.4g, s^2/n %.4g, ratio %.3f\n", sampler.c_str(), r.error.meanVariance,
                    sampleVariance, r.error.meanVariance / sampleVariance);
        return r.error.meanVariance / sampleVariance;
    };
    EXPECT_LT(ratio("sobol"), 0.5);
    EXPECT_LT(ratio("halton"), 0.5);
    // 256 pixels of 7 degrees of freedom each: the ratio's relative error is about 6%.
    EXPECT_NEAR(ratio("independent"), 1.0, 0.25);
}

// A render stopped by its time budget long before its --spp (as `--time` with an unbounded
// --spp is used) fills every scrambled set and batch alike: its variance estimates equal a
// finished render's of about the same count, to within their own noise. With sets as ranges
// of the --spp indices only the first set was filled, and every estimate was 0.
TEST(TechniqueFigures, TimeBudgetedRenderEstimatesItsVariance) {
    const SceneRenders s(manyLightsScene(), "path");  // 576 pixels: the pixels' mean variance to ~5%
    RenderOptions budget;
    budget.spp = 1 << 24;
    budget.timeLimit = 0.4;
    budget.seed = 2;
    budget.sampler = "sobol";
    budget.progress = false;
    budget.techniqueFigures = true;
    budget.batches = batchCount(budget.spp);
    budget.scramblings = scramblingCount(budget.sampler, budget.spp);
    const RenderResult stopped = render(*s.scene, *s.integrator, budget);
    ASSERT_LT(stopped.meanSpp, budget.spp);
    ASSERT_GE(stopped.meanSpp, 16) << "too slow a machine for this test's budget";
    const int spp = int(stopped.meanSpp);
    const RenderResult finished = s.run("sobol", spp, 3);
    // Per-sample variances (times the count), pixel and technique figures alike.
    const double a = stopped.error.meanVariance * stopped.meanSpp, b = finished.error.meanVariance * spp;
    std::printf("stopped at %.1f spp: variance x spp %.4g, finished: %.4g\n", stopped.meanSpp, a, b);
    // Loose: 8 sets per pixel, and the two renders' points differ (a 2^24 sequence stopped
    // against a finished one of spp); measured 0.74-0.98 under load. Broken, a is 0.
    EXPECT_NEAR(a / b, 1.0, 0.5);
    ASSERT_EQ(stopped.techniqueFigures.size(), finished.techniqueFigures.size());
    for (size_t t = 0; t < finished.techniqueFigures.size(); ++t) {
        const double va = stopped.techniqueFigures[t].variance * stopped.meanSpp,
                     vb = finished.techniqueFigures[t].variance * spp;
        std::printf("  figure %zu: variance x spp %.4g, finished %.4g\n", t, va, vb);
        // One image-wide variance from 8 sets each (7 degrees of freedom): a ratio of two
        // such falls outside [1/12, 12] with a chance of about 1e-3.
        EXPECT_GT(va, vb / 12) << "figure " << t;
        EXPECT_LT(va, vb * 12) << "figure " << t;
    }
}

}  // namespace
