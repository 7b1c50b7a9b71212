// Adaptive sampling at equal time (thesis ch. 2 and §5.3.1): uniform, sequential and
// two-stage sample allocation each render the scene for the same wall time; RMSE and
// relative MSE against a long uniform reference (rendered once, cached) say which spends
// the time best. Results are averaged over --runs independent seeds.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "image/image.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/renderer.h"
#include "util/error.h"

using namespace ps;

namespace {

struct Errors {
    double mse = 0;     // over all channels
    double relMse = 0;  // per pixel (x - r)^2 / (r^2 + 0.01), luminance: the error adaptive sampling targets
    double bias = 0;    // mean (x - r) / mean r, luminance
};

Errors compare(const Image& img, const Image& ref) {
    Errors e;
    double sumRef = 0;
    size_t n = size_t(ref.width) * ref.height;
    for (size_t i = 0; i < ref.rgb.size(); ++i) e.mse += double(img.rgb[i] - ref.rgb[i]) * double(img.rgb[i] - ref.rgb[i]);
    e.mse /= double(ref.rgb.size());
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            double a = img.get(x, y).luminance(), r = ref.get(x, y).luminance();
            e.relMse += (a - r) * (a - r) / (r * r + 0.01);
            e.bias += a - r;
            sumRef += r;
        }
    e.relMse /= double(n);
    e.bias /= sumRef;
    return e;
}

RenderResult renderScene(const Scene& scene, AdaptiveMode mode, int spp, double seconds, int threads, uint64_t seed) {
    auto integrator = createIntegrator("path", scene);
    RenderOptions o;
    o.spp = spp;
    o.timeLimit = seconds;
    o.threads = threads;
    o.seed = seed;
    o.sampler = scene.settings().sampler;
    o.progress = false;
    o.adaptive = mode;
    return render(scene, *integrator, o);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Adaptive sampling at equal time: uniform vs sequential vs two-stage, RMSE against a reference"};
    std::string scenePath = PATHSPACE_SOURCE_DIR "/../shared/scenes/veach-mis/scene-v4-320x180.pbrt";
    if (!std::filesystem::exists(scenePath)) scenePath = PATHSPACE_SOURCE_DIR "/scenes/cornell-box.pbrt";
    std::string cacheDir = PATHSPACE_BENCH_CACHE, jsonPath;
    double seconds = 5;
    int threads = 2, refSpp = 4096, runs = 3;
    app.add_option("scene", scenePath, "Scene file (default: shared veach-mis 320x180, else scenes/cornell-box.pbrt)");
    app.add_option("--time", seconds, "Render time per mode and run, seconds");
    app.add_option("--threads", threads, "Worker threads");
    app.add_option("--runs", runs, "Independent runs (seeds) per mode; errors are averaged");
    app.add_option("--ref-spp", refSpp, "Samples per pixel of the uniform reference (rendered once, then cached)");
    app.add_option("--cache", cacheDir, "Directory for the cached reference");
    app.add_option("--json", jsonPath, "Write the results as JSON");
    CLI11_PARSE(app, argc, argv);
    try {
        setWarningsQuiet(true);
        auto scene = buildScene(parseSceneFile(scenePath));
        scene->settings().integrator = "path";
        std::filesystem::create_directories(cacheDir);
        std::string refPath = cacheDir + "/" + std::filesystem::path(scenePath).stem().string() + "-" +
                              std::filesystem::path(scenePath).parent_path().filename().string() + "-ref" +
                              std::to_string(refSpp) + ".pfm";
        if (!std::filesystem::exists(refPath)) {
            std::printf("rendering the reference (%d spp) to %s ...\n", refSpp, refPath.c_str());
            std::fflush(stdout);
            RenderResult ref = renderScene(*scene, AdaptiveMode::None, refSpp, 0, threads, 987654321);
            writeImage(refPath, ref.image);
            std::printf("reference: %.1f s\n", ref.seconds);
        }
        Image ref = readImage(refPath);
        std::printf("scene %s, %.1f s per render, %d run(s), reference %d spp\n", scenePath.c_str(), seconds, runs, refSpp);
        std::printf("%-10s %8s %8s %10s %10s %10s %10s %9s\n", "mode", "spp", "seconds", "RMSE", "MSE ratio", "relMSE",
                    "relMSE rt", "bias");
        const std::pair<const char*, AdaptiveMode> modes[] = {
            {"uniform", AdaptiveMode::None}, {"sequential", AdaptiveMode::Sequential}, {"twostage", AdaptiveMode::TwoStage}};
        nlohmann::json rows = nlohmann::json::array();
        Errors base;
        for (const auto& [name, mode] : modes) {
            Errors avg;
            double spp = 0, secs = 0;
            for (int k = 0; k < runs; ++k) {
                RenderResult r = renderScene(*scene, mode, 1 << 24, seconds, threads, 1 + uint64_t(k));
                if (r.image.width != ref.width || r.image.height != ref.height)
                    throw InputError("the reference's resolution differs from the scene's");
                Errors e = compare(r.image, ref);
                avg.mse += e.mse / runs;
                avg.relMse += e.relMse / runs;
                avg.bias += e.bias / runs;
                spp += r.meanSpp / runs;
                secs += r.seconds / runs;
            }
            if (mode == AdaptiveMode::None) base = avg;
            std::printf("%-10s %8.1f %8.2f %10.5f %10.3f %10.5f %10.3f %+8.4f\n", name, spp, secs, std::sqrt(avg.mse),
                        avg.mse / base.mse, avg.relMse, avg.relMse / base.relMse, avg.bias);
            rows.push_back({{"mode", name}, {"spp", spp}, {"seconds", secs}, {"rmse", std::sqrt(avg.mse)},
                            {"mse_ratio", avg.mse / base.mse}, {"relative_mse", avg.relMse},
                            {"relative_mse_ratio", avg.relMse / base.relMse}, {"relative_bias", avg.bias}});
        }
        if (!jsonPath.empty())
            std::ofstream(jsonPath) << nlohmann::json{{"scene", scenePath}, {"seconds", seconds}, {"runs", runs},
                                                      {"reference_spp", refSpp}, {"results", rows}}
                                           .dump(2);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
