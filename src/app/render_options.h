// The options of `pathspace render`, shared by the command line and the Python module
// (src/python): their values, their definitions and checks (one set of rules and messages),
// how they make a render of a built scene, and the statistics `--stats` writes.
#pragma once
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

#include "transport/adaptive.h"
#include "transport/renderer.h"

namespace ps {

class BDPTIntegrator;

// The options' values as parsed; an unset option keeps its "unset" value here.
struct RenderArgs {
    int spp = 0;
    double time = 0;
    int threads = 0;
    long long seed = -1;
    int maxDepth = -1;
    std::string integrator;
    std::string mis;  // empty: the default (power, beta 2)
    float lightPaths = 0;  // --light-paths (bdpt): 0 = not given (one light subpath per sample)
    bool lightPathsAuto = false;  // --light-paths auto: chosen by a pilot (transport/light_path_choice.h)
    float shadowRoulette = 0;  // --shadow-roulette: 0 = off
    int lightSamples = 0;      // --light-samples (path): 0 = not given (one light sample per vertex)
    std::string strategiesDir;
    bool keepStrategies = false;  // strategy images kept in memory (the Python module), not written
    std::string sampler;
    std::string color = "spectral";
    std::string adaptive;
    std::vector<std::string> aovs;
    std::vector<std::string> outputs;
    std::vector<float> crop;
    std::vector<int> pixelBounds;  // --pixelbounds x0 x1 y0 y1
    std::string statsFile;
    bool statsPrint = false;  // `--stats` without a file
    std::string checkpoint, resume;  // --checkpoint FILE, --resume FILE
    double checkpointEvery = -1;     // --checkpoint-every SECONDS
    std::string maxMemory;           // --max-memory SIZE, checked by parseByteSize
    // Metropolis parameters (override the scene's Integrator "pssmlt"/"mlt" ones); unset when < 0.
    int chains = -1;
    int bootstrap = -1;
    double largeStepProbability = -1;
    double cameraStepProbability = -1;
    double strategyPilot = -1;
    double twoStage = -1;
    double twoStageBlackLevel = -1;
    double sigma = -1;
    int mltDirect = -1;        // --mlt-direct N
    std::string mltMutations;  // --mlt-mutations KEY=VALUE,...
    bool quiet = false;

    bool spectral() const { return color == "spectral"; }
    bool stats() const { return statsPrint || !statsFile.empty(); }
    bool strategyImages() const { return !strategiesDir.empty() || keepStrategies; }
    bool varianceImage() const;  // --aov variance
};

// Adds every option of `pathspace render` but the scene file to `cmd`, each with its check and
// help group.
void addRenderOptions(CLI::App* cmd, RenderArgs& args);

// What the options make of a scene.
struct RenderSetup {
    std::unique_ptr<Integrator> integrator;
    RenderOptions opts;  // all but the checkpoints'
    BDPTIntegrator* bdpt = nullptr;  // the integrator, when it records strategy images
    bool choosesLightPaths = false;  // --light-paths auto: a pilot chooses before the render
};

// Applies the options to a scene built in their colour mode (its settings and pixels), makes
// the integrator and the render's options, and warns of what the integrator cannot render.
// Throws InputError for a combination the render refuses. Alike on every process.
void configureRender(Scene& scene, const RenderArgs& args, RenderSetup& setup);

// After render(): the statistics count every collective of the render (the last ones
// included) and a crop keeps its place in the film (an EXR's data window inside its display
// window).
void completeResult(const Scene& scene, RenderResult& r);

// What the noise figures of a result can say: a variance needs two samples of a pixel; after
// --resume it covers the earlier runs' samples too, and this run's time alone would overstate
// the efficiency 1/(V T), which is then not given.
struct NoiseKnown {
    bool noise = false, resumed = false, efficiency = false;
};
NoiseKnown noiseKnown(const RenderResult& r);

// Film "maxcomponentvalue" makes a biased image: said wherever its numbers are read.
constexpr const char* kClampNote = "biased: energy is lost where the clamp acts";

// The statistics as `--stats` writes them. `run` is this run's share of r.stats (after
// --resume the rest was the earlier runs').
nlohmann::json renderStatistics(const Scene& scene, const RenderArgs& args, const RenderSetup& setup,
                                const RenderResult& r, const PathStats& run, const std::string& sceneFile,
                                const std::vector<std::string>& outputs, bool interrupted);

}  // namespace ps
