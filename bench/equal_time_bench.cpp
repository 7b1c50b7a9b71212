// Equal-time comparison of integrators on one scene: each renders for the same wall time,
// and its RMSE against a long reference render says which converges faster there
// (efficiency in the thesis' sense, §2.4: error at equal cost).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "image/image.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/renderer.h"
#include "util/error.h"

using namespace ps;

static double rmse(const Image& a, const Image& b) {
    double s = 0;
    size_t n = a.rgb.size();
    for (size_t i = 0; i < n; ++i) s += double(a.rgb[i] - b.rgb[i]) * double(a.rgb[i] - b.rgb[i]);
    return std::sqrt(s / double(n));
}

// Relative MSE: per pixel and channel (x - ref)^2 / (ref^2 + 0.01), averaged. With the
// reference's own variance per pixel (its --aov variance image, of the mean luminance), that
// variance is subtracted: E[(x - ref)^2] = MSE(x) + Var(ref) for independent renders, so the
// reference's noise does not put a floor under the figure.
static double relativeMse(const Image& x, const Image& ref, const Image* refVariance) {
    double s = 0;
    size_t n = x.rgb.size();
    for (size_t i = 0; i < n; ++i) {
        double d = double(x.rgb[i]) - ref.rgb[i];
        double e = d * d - (refVariance ? double(refVariance->rgb[i]) : 0.0);
        s += e / (double(ref.rgb[i]) * ref.rgb[i] + 0.01);
    }
    return s / double(n);
}

static double imageMean(const Image& img) {
    double m = 0;
    for (float v : img.rgb) m += v / double(img.rgb.size());
    return m;
}

int main(int argc, char** argv) {
    CLI::App app{"Equal-time benchmark: error against a reference for each integrator at the same render time"};
    std::string scenePath, refPath, refVariancePath, jsonPath;
    double seconds = 20;
    int threads = 2, seeds = 1;
    std::vector<std::string> integrators = {"path", "bdpt"};
    app.add_option("scene", scenePath, "Scene file")->required();
    app.add_option("reference", refPath, "Reference image of the same scene (EXR/PFM)")->required();
    app.add_option("--reference-variance", refVariancePath,
                   "The reference's per-pixel variance image (pathspace render --aov variance), subtracted from the "
                   "relative MSE");
    app.add_option("--time", seconds, "Render time per integrator, seconds (Metropolis: bootstrap included)");
    app.add_option("--threads", threads, "Worker threads");
    app.add_option("--seeds", seeds, "Renders per integrator (seeds 1..N): mean error and the image mean's spread");
    app.add_option("--integrators", integrators,
                   "Integrators to compare (mlt:KEY=VALUE,... is mlt with those --mlt-mutations weights)");
    app.add_option("--json", jsonPath, "Write the results as JSON");
    std::string color = "rgb";
    app.add_option("--color", color,
                   "Colour mode: rgb (the default here, that of the figures in bench/README.md before 2026-12-03) "
                   "or spectral (the renderer's default)")
        ->check(CLI::IsMember({"rgb", "spectral"}));
    int chains = 0, bootstrap = 0;
    double largeStep = -1, sigma = 0, cameraSteps = -1;
    app.add_option("--chains", chains, "Metropolis: chains (default: the scene's)");
    app.add_option("--bootstrap", bootstrap, "Metropolis: bootstrap samples (default: the scene's)");
    app.add_option("--large-step-probability", largeStep, "Metropolis: large-step probability (default: the scene's)");
    app.add_option("--sigma", sigma, "Metropolis: small-step sigma (default: the scene's)");
    app.add_option("--camera-step-probability", cameraSteps,
                   "pssmlt, mmlt: share of small steps that move only the camera subpath (default 0.5)");
    double strategyPilot = -1;
    std::string savePrefix;
    app.add_option("--save", savePrefix, "Also write each render as PREFIX-INTEGRATOR-SEED.pfm (and the reference as PREFIX-ref.pfm)");
    app.add_option("--strategy-pilot", strategyPilot, "mmlt: the bootstrap's share that learns the strategy choice");
    std::vector<std::string> external;
    app.add_option("--compare", external,
                   "Also score these images (e.g. another renderer's equal-time renders of the scene): relative MSE "
                   "after scaling each channel to the reference's channel mean (a spectral renderer's colours differ "
                   "by a few percent), and the image mean before that");
    CLI11_PARSE(app, argc, argv);
    try {
        setWarningsQuiet(true);
        Image ref = readImage(refPath);
        Image refVariance;
        if (!refVariancePath.empty()) refVariance = readImage(refVariancePath);
        const bool spectral = color == "spectral";
        auto scene = buildScene(parseSceneFile(scenePath), spectral);
        RenderSettings& st = scene->settings();
        st.spectral = spectral;
        if (chains > 0) st.mltChains = chains;
        if (bootstrap > 0) st.mltBootstrapSamples = bootstrap;
        if (largeStep >= 0) st.mltLargeStepProbability = float(largeStep);
        if (sigma > 0) st.mltSigma = float(sigma);
        if (cameraSteps >= 0) st.mltCameraStepProbability = float(cameraSteps);
        if (strategyPilot >= 0) st.mltStrategyPilot = float(strategyPilot);
        const double refMean = imageMean(ref);
        if (!savePrefix.empty()) writeImage(savePrefix + "-ref.pfm", ref);
        nlohmann::json rows = nlohmann::json::array();
        std::printf("%-8s %5s %10s %8s %10s %10s %10s %11s  %s\n", "integ", "seed", "spp", "seconds", "rel RMSE",
                    "relMSE", "mean/ref", "acceptance", "relMSE ratio to first");
        double firstRelMse = 0;
        for (const std::string& name : integrators) {
            // "mlt:WEIGHTS": mlt with --mlt-mutations WEIGHTS (for the mutations' ablation);
            // "NAME:two-stage=F": with --two-stage F.
            auto integrator = createIntegrator(applyIntegratorVariant(name, scene->settings()), *scene);
            double sumRelMse = 0, sumMean = 0, sumMean2 = 0;
            for (int k = 1; k <= seeds; ++k) {
                RenderOptions o;
                o.spp = 1 << 20;
                o.timeLimit = seconds;
                o.threads = threads;
                o.seed = uint64_t(k);
                o.sampler = scene->settings().sampler;
                o.progress = false;
                RenderResult r = render(*scene, *integrator, o);
                if (r.image.width != ref.width || r.image.height != ref.height)
                    throw InputError("the reference's resolution differs from the scene's");
                if (!savePrefix.empty()) writeImage(savePrefix + "-" + name + "-" + std::to_string(k) + ".pfm", r.image);
                double e = rmse(r.image, ref);
                double rel = relativeMse(r.image, ref, refVariancePath.empty() ? nullptr : &refVariance);
                double meanRatio = imageMean(r.image) / refMean;
                sumRelMse += rel;
                sumMean += meanRatio;
                sumMean2 += meanRatio * meanRatio;
                double acceptance = r.metropolis.present ? r.metropolis.acceptanceRate() : 0.0;
                std::printf("%-8s %5d %10.1f %8.2f %10.4f %10.4g %10.4f %11.3f\n", name.c_str(), k, r.meanSpp, r.seconds,
                            e / refMean, rel, meanRatio, acceptance);
                rows.push_back({{"integrator", name}, {"seed", k}, {"spp", r.meanSpp}, {"seconds", r.seconds},
                                {"rmse", e}, {"relative_rmse", e / refMean}, {"relative_mse", rel},
                                {"mean_ratio", meanRatio}, {"acceptance", acceptance}});
            }
            double relMse = sumRelMse / seeds, mean = sumMean / seeds;
            double spread = seeds > 1 ? std::sqrt(std::max(0.0, (sumMean2 - seeds * mean * mean) / (seeds - 1))) : 0.0;
            if (firstRelMse == 0) firstRelMse = relMse;
            std::printf("%-8s  mean relMSE %.4g (%.3f of %s's), image mean / ref %.4f, its spread across seeds %.4f\n",
                        name.c_str(), relMse, relMse / firstRelMse, integrators[0].c_str(), mean, spread);
        }
        for (const std::string& path : external) {
            Image img = readImage(path);
            if (img.width != ref.width || img.height != ref.height)
                throw InputError(path + ": the resolution differs from the reference's");
            const double meanRatio = imageMean(img) / refMean;
            double own[3] = {0, 0, 0}, theirs[3] = {0, 0, 0};
            for (size_t i = 0; i < img.rgb.size(); ++i) {
                own[i % 3] += ref.rgb[i];
                theirs[i % 3] += img.rgb[i];
            }
            for (size_t i = 0; i < img.rgb.size(); ++i)
                img.rgb[i] = float(img.rgb[i] * (theirs[i % 3] > 0 ? own[i % 3] / theirs[i % 3] : 1.0));
            double rel = relativeMse(img, ref, refVariancePath.empty() ? nullptr : &refVariance);
            std::printf("%-40s relMSE %.4g (%.3f of %s's, channels scaled by %.4f %.4f %.4f), image mean / ref %.4f\n",
                        path.c_str(), rel, firstRelMse > 0 ? rel / firstRelMse : 0.0, integrators.empty() ? "" : integrators[0].c_str(),
                        own[0] / theirs[0], own[1] / theirs[1], own[2] / theirs[2], meanRatio);
            rows.push_back({{"image", path}, {"relative_mse", rel}, {"mean_ratio", meanRatio}});
        }
        if (!jsonPath.empty()) std::ofstream(jsonPath) << nlohmann::json{{"scene", scenePath}, {"results", rows}}.dump(2);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
