// Equal-time comparison of integrators on one scene: each renders for the same wall time,
// and its RMSE against a long reference render says which converges faster there
// (efficiency in the thesis' sense, §2.4: error at equal cost).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

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

int main(int argc, char** argv) {
    CLI::App app{"Equal-time benchmark: RMSE against a reference for each integrator at the same render time"};
    std::string scenePath, refPath, jsonPath;
    double seconds = 20;
    int threads = 2;
    std::vector<std::string> integrators = {"path", "bdpt"};
    app.add_option("scene", scenePath, "Scene file")->required();
    app.add_option("reference", refPath, "Reference image of the same scene (EXR/PFM)")->required();
    app.add_option("--time", seconds, "Render time per integrator, seconds");
    app.add_option("--threads", threads, "Worker threads");
    app.add_option("--integrators", integrators, "Integrators to compare");
    app.add_option("--json", jsonPath, "Write the results as JSON");
    CLI11_PARSE(app, argc, argv);
    try {
        setWarningsQuiet(true);
        Image ref = readImage(refPath);
        auto scene = buildScene(parseSceneFile(scenePath));
        double refMean = 0;
        for (float v : ref.rgb) refMean += v / double(ref.rgb.size());
        nlohmann::json rows = nlohmann::json::array();
        std::printf("%-8s %10s %10s %12s %10s\n", "integ", "spp", "seconds", "RMSE", "rel RMSE");
        double firstMse = 0;
        for (const std::string& name : integrators) {
            auto integrator = createIntegrator(name, *scene);
            RenderOptions o;
            o.spp = 1 << 20;
            o.timeLimit = seconds;
            o.threads = threads;
            o.seed = 1;
            o.sampler = scene->settings().sampler;
            o.progress = false;
            RenderResult r = render(*scene, *integrator, o);
            if (r.image.width != ref.width || r.image.height != ref.height)
                throw InputError("the reference's resolution differs from the scene's");
            double e = rmse(r.image, ref);
            if (firstMse == 0) firstMse = e * e;
            std::printf("%-8s %10.1f %10.2f %12.5f %10.4f   MSE ratio to %s: %.3f\n", name.c_str(), r.meanSpp, r.seconds, e,
                        e / refMean, integrators[0].c_str(), e * e / firstMse);
            rows.push_back({{"integrator", name}, {"spp", r.meanSpp}, {"seconds", r.seconds}, {"rmse", e},
                            {"relative_rmse", e / refMean}});
        }
        if (!jsonPath.empty()) std::ofstream(jsonPath) << nlohmann::json{{"scene", scenePath}, {"results", rows}}.dump(2);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
