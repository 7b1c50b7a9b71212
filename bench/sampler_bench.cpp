// Compares the samplers on one scene at equal sample count: error against a high-sample
// reference (rendered once and cached), render time, and efficiency 1 / (MSE T) (thesis
// eq. 2.26), each also as a ratio to independent sampling.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "image/image.h"
#include "mc/sampler.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/renderer.h"
#include "util/error.h"

using namespace ps;

namespace {

// The shared Cornell box when present, else the one shipped in scenes/.
std::string defaultScene() {
    std::string shared = PATHSPACE_SHARED_DIR "/scenes/cornell-box/scene-v4-256.pbrt";
    return std::filesystem::exists(shared) ? shared : PATHSPACE_SOURCE_DIR "/scenes/cornell-box.pbrt";
}

struct Setup {
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Integrator> integrator;
};

Setup load(const std::string& path, int maxDepth) {
    Setup s;
    s.scene = buildScene(parseSceneFile(path));
    if (maxDepth >= 0) s.scene->settings().maxDepth = maxDepth;
    s.integrator = createIntegrator("path", *s.scene);
    return s;
}

RenderResult renderWith(const Setup& s, const std::string& sampler, int spp, uint64_t seed, int threads) {
    RenderOptions o;
    o.spp = spp;
    o.seed = seed;
    o.sampler = sampler;
    o.threads = threads;
    o.progress = false;
    return render(*s.scene, *s.integrator, o);
}

double meanSquaredError(const Image& a, const Image& b) {
    double sum = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        double d = double(a.rgb[i]) - b.rgb[i];
        sum += d * d;
    }
    return sum / double(a.rgb.size());
}

// The reference depends on everything that changes its image; its file name carries a hash
// of those, so a changed setting renders a new one. Bump kReferenceVersion when the
// reference's sampler or the renderer changes.
constexpr int kReferenceVersion = 2;
std::string referencePath(const std::string& dir, const std::string& scene, int spp, int maxDepth) {
    std::string key = std::to_string(kReferenceVersion) + "|" + std::filesystem::absolute(scene).string() + "|" +
                      std::to_string(spp) + "|" +
                      std::to_string(maxDepth) + "|" + std::to_string(std::filesystem::file_size(scene));
    uint64_t h = 1469598103934665603ULL;  // FNV-1a
    for (unsigned char c : key) h = (h ^ c) * 1099511628211ULL;
    char name[64];
    std::snprintf(name, sizeof name, "sampler_bench_ref_%016llx.pfm", (unsigned long long)h);
    return (std::filesystem::path(dir) / name).string();
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Sampler benchmark: error, time and efficiency of every sampler at equal sample count"};
    std::string scenePath = defaultScene(), cacheDir = PATHSPACE_BENCH_CACHE_DIR, json;
    int spp = 16, refSpp = 1024, runs = 4, maxDepth = -1, threads = 2;
    app.add_option("scene", scenePath, "Scene file");
    app.add_option("--spp", spp, "Samples per pixel of the compared renders");
    app.add_option("--ref-spp", refSpp, "Samples per pixel of the reference (sobol)");
    app.add_option("--runs", runs, "Renders per sampler (seeds 1..runs); MSE and time are averaged");
    app.add_option("--maxdepth", maxDepth, "Maximum depth (default: the scene's)");
    app.add_option("--threads", threads, "Threads");
    app.add_option("--cache-dir", cacheDir, "Where the reference image is kept");
    app.add_option("--json", json, "Write results as JSON");
    CLI11_PARSE(app, argc, argv);
    setWarningsQuiet(true);
    try {
        Setup setup = load(scenePath, maxDepth);
        const int depth = setup.scene->settings().maxDepth;
        std::string refFile = referencePath(cacheDir, scenePath, refSpp, depth);
        Image ref;
        if (std::filesystem::exists(refFile)) {
            ref = readImage(refFile);
            std::printf("reference: %s (cached)\n", refFile.c_str());
        } else {
            std::printf("reference: rendering %d spp with sobol...\n", refSpp);
            std::fflush(stdout);
            RenderResult r = renderWith(setup, "sobol", refSpp, 1000003, threads);
            ref = r.image;
            writeImage(refFile, ref);
            std::printf("reference: %s (%.1f s)\n", refFile.c_str(), r.seconds);
        }

        // Rounds over all samplers rather than all runs of one sampler after another, so
        // drifts in machine speed spread over every sampler alike.
        const std::vector<std::string>& names = samplerNames();
        std::map<std::string, double> mse, seconds;
        for (int run = 0; run < runs; ++run)
            for (const std::string& name : names) {
                RenderResult r = renderWith(setup, name, spp, uint64_t(run + 1), threads);
                if (r.image.rgb.size() != ref.rgb.size()) throw InputError("reference size differs from the render");
                mse[name] += meanSquaredError(r.image, ref) / runs;
                seconds[name] += r.seconds / runs;
            }

        double mseInd = mse["independent"], effInd = 1 / (mse["independent"] * seconds["independent"]);
        std::printf("\n%s, %d spp, maxdepth %d, %d threads, mean of %d runs; reference %d spp (sobol)\n\n",
                    scenePath.c_str(), spp, depth, threads, runs, refSpp);
        std::printf("| sampler | RMSE | time (s) | MSE / independent | efficiency 1/(MSE T) | efficiency / independent |\n");
        std::printf("|---|---|---|---|---|---|\n");
        nlohmann::json out = {{"scene", scenePath}, {"spp", spp}, {"ref_spp", refSpp}, {"maxdepth", depth},
                              {"threads", threads}, {"runs", runs}, {"samplers", nlohmann::json::array()}};
        for (const std::string& name : names) {
            double eff = 1 / (mse[name] * seconds[name]);
            std::printf("| %s | %.5f | %.3f | %.3f | %.4g | %.2f |\n", name.c_str(), std::sqrt(mse[name]), seconds[name],
                        mse[name] / mseInd, eff, eff / effInd);
            out["samplers"].push_back({{"sampler", name}, {"rmse", std::sqrt(mse[name])}, {"seconds", seconds[name]},
                                       {"mse_ratio", mse[name] / mseInd}, {"efficiency", eff},
                                       {"efficiency_ratio", eff / effInd}});
        }
        if (!json.empty()) std::ofstream(json) << out.dump(2) << "\n";
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
}
