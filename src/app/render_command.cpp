#include "app/render_command.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <span>
#include <unistd.h>

#include <tbb/task_arena.h>

#include "app/command_line.h"
#include "app/exit_codes.h"
#include "app/output_checks.h"
#include "image/image.h"
#include "mc/sampler.h"
#include "render/distributed.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/bdpt.h"
#include "transport/checkpoint.h"
#include "transport/coverage.h"
#include "transport/integrator.h"
#include "transport/renderer.h"
#include "util/error.h"
#include "util/input_files.h"
#include "util/memory_limit.h"

namespace ps {

namespace {

std::atomic<bool> gInterrupt{false};

// First signal: stop and write what we have. Second: leave at once.
extern "C" void onSignal(int) {
    if (gInterrupt.exchange(true)) _exit(kExitInterrupted);
}

// CLI11's own range checks print the range's limits as 300-digit numbers; these say it plainly.
// A validator that accepts the text when ok(text), else says "expected WHAT, got TEXT".
template <typename Ok>
CLI::Validator plainCheck(const std::string& what, const std::string& name, Ok ok) {
    return CLI::Validator(
        [what, ok](std::string& text) -> std::string {
            return ok(text) ? std::string() : "expected " + what + ", got " + quoteForMessage(text);
        },
        name);
}

// The whole text is a finite number.
bool parseNumber(const std::string& text, double& v) {
    char* end = nullptr;
    v = std::strtod(text.c_str(), &end);
    return end != text.c_str() && *end == '\0' && std::isfinite(v);
}

CLI::Validator numberCheck(bool allowZero) {
    return plainCheck(allowZero ? "a number >= 0" : "a positive number", allowZero ? "NUMBER>=0" : "NUMBER>0",
                      [allowZero](const std::string& t) {
                          double v;
                          return parseNumber(t, v) && (allowZero ? v >= 0 : v > 0);
                      });
}

CLI::Validator probabilityCheck() {
    return plainCheck("a probability in [0, 1]", "P in [0,1]", [](const std::string& t) {
        double v;
        return parseNumber(t, v) && v >= 0 && v <= 1;
    });
}

// A whole number in [lo, hi] (CLI11 would truncate "2.5" for an int, or say "Could not
// convert"; a seed past 2^63 - 1 would be clamped in silence).
CLI::Validator wholeCheck(long long lo, long long hi = 2147483647LL) {
    const std::string range = hi == 2147483647LL ? ">= " + std::to_string(lo)
                                                 : "from " + std::to_string(lo) + " to " + std::to_string(hi);
    return plainCheck("a whole number " + range, "INT>=" + std::to_string(lo),
                      [lo, hi](const std::string& t) {
                          errno = 0;
                          char* end = nullptr;
                          long long v = std::strtoll(t.c_str(), &end, 10);
                          return errno == 0 && end != t.c_str() && *end == '\0' && v >= lo && v <= hi;
                      });
}
CLI::Validator countCheck() { return wholeCheck(1); }

// out.exr -> out.variance.exr, next to the output and in its format.
std::string variancePath(const std::string& output) {
    std::filesystem::path p(output);
    return (p.parent_path() / (p.stem().string() + ".variance" + p.extension().string())).string();
}

// Every other file the scene read (included scene files, meshes, images, lens and spectrum
// files): its path relative to the scene file's directory -> the hash of its bytes.
nlohmann::json inputFileHashes(const std::string& sceneFile) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path scene = fs::weakly_canonical(sceneFile, ec);
    const fs::path base = scene.parent_path();
    nlohmann::json files = nlohmann::json::object();
    for (const std::string& f : inputFiles()) {
        const fs::path p = fs::weakly_canonical(f, ec);
        if (p == scene) continue;
        files[p.lexically_relative(base).generic_string()] = fileHash(f);
    }
    return files;
}

// One voice per job: the warnings of the other processes (which print none) reach rank 0,
// which prints each it has not given itself (most, from parsing the scene, every process
// meets) and counts it.
void gatherWarnings() {
    if (distributed::size() == 1) return;
    distributed::Purpose purpose("warnings");
    std::vector<char> mine;
    if (!distributed::isRoot())
        for (const std::string& w : warningMessages()) mine.insert(mine.end(), w.c_str(), w.c_str() + w.size() + 1);
    const std::vector<char> all = distributed::gatherBytesToRoot(mine);
    for (size_t at = 0; at < all.size();) {
        const std::string w(all.data() + at);
        warning(w);
        at += w.size() + 1;
    }
}

// The summary's first line: what ran, as the user would name it.
std::string summaryLine(const RenderSettings& s, int threads) {
    static const std::map<std::string, std::string> kNames = {
        {"path", "path tracing"},           {"light", "light tracing"},
        {"bdpt", "bidirectional path tracing"}, {"pssmlt", "primary-sample-space MLT"},
        {"mmlt", "multiplexed MLT"},        {"mlt", "Veach's MLT"}};
    auto it = kNames.find(s.integrator);
    std::string line = "integrator " + s.integrator + " (" + (it != kNames.end() ? it->second : s.integrator);
    if (s.sceneIntegrator == "mlt" && s.integrator == "mmlt") line += ": the scene's Integrator \"mlt\", pbrt-v4's";
    line += ")";
    // The Metropolis integrators draw their own primary samples; the pixel sampler is unused.
    if (s.integrator == "path" || s.integrator == "light" || s.integrator == "bdpt") line += " | sampler " + s.sampler;
    line += std::string(" | ") + (s.spectral ? "spectral" : "rgb") + " colour | " + std::to_string(threads) +
            (threads == 1 ? " thread" : " threads");
    return line;
}

}  // namespace

// What the scene file and the options make, alike on every process.
struct RenderCommand::Job {
    std::unique_ptr<Scene> scene;
    std::vector<std::string> outputs;
    bool writeVariance = false;
    std::unique_ptr<Integrator> integrator;
    RenderOptions opts;  // all but the checkpoints'
    BDPTIntegrator* bdpt = nullptr;  // the integrator, when it records strategy images
    nlohmann::json checkpointSettings;  // what must match to resume
};

void RenderCommand::attach(CLI::App& app) {
    cmd_ = app.add_subcommand("render", "Render a pbrt-v4 scene file");
    cmd_->add_option("scene", scene_, "pbrt-v4 scene file")->required()->check(CLI::ExistingFile);
    cmd_->add_option("--spp", spp_, "Samples per pixel (overrides the scene's Sampler pixelsamples)")->check(wholeCheck(1));
    cmd_->add_option("--time", time_, "Time budget in seconds; the image so far is written when it runs out")
        ->check(numberCheck(false));
    cmd_->add_option("--threads,--nthreads", threads_,
                     "Worker threads (default: all cores; more than the machine has are cut to that)")
        ->check(wholeCheck(0));
    cmd_->add_option("--seed", seed_, "Random seed (overrides the scene's; the same seed gives the same image)")
        ->check(wholeCheck(0, 9223372036854775807LL));
    cmd_->add_option("--maxdepth", maxDepth_, "Maximum number of scattering events (overrides the scene's)")
        ->check(wholeCheck(0));
    cmd_->add_option("--integrator", integrator_,
                     "Integrator: path (path tracing with MIS), light (light tracing: particles from the lights "
                     "splatted through the lens), bdpt (bidirectional path tracing, every strategy with MIS), pssmlt "
                     "(primary-sample-space Metropolis light transport over BDPT), mmlt (multiplexed Metropolis: the "
                     "chains also choose the path depth and one BDPT strategy), mlt (Veach's Metropolis light transport: "
                     "chains over paths themselves, changed by path-space mutations); for the Metropolis integrators "
                     "--spp sets the mutations per pixel. pbrt names volpath and lightpath map to path and light (a "
                     "scene's Integrator \"mlt\" is pbrt-v4's multiplexed MLT: mmlt)")
        ->check(CLI::IsMember({"path", "volpath", "light", "lightpath", "bdpt", "pssmlt", "mmlt", "mlt"}));
    cmd_->add_option("--bdpt-strategies", strategiesDir_,
                     "With --integrator bdpt: also write, into this directory, one EXR per strategy (s light "
                     "vertices, t camera vertices) up to path depth 5, MIS-weighted (s<S>_t<T>.exr) and "
                     "unweighted (s<S>_t<T>_unweighted.exr); the weighted ones sum to the image");
    cmd_->add_option("--mis", mis_, "BDPT's weighting of strategies: power (default), balance, none (uniform)")
        ->check(CLI::IsMember({"power", "balance", "none"}));
    cmd_->add_option("--sampler", sampler_,
                     "Sample placement per pixel: sobol (default; Owen-scrambled Sobol, padded), zsobol (Sobol in "
                     "Morton order over the image: blue-noise error), halton (Owen-scrambled Halton), orthogonal "
                     "(randomised orthogonal arrays), stratified (jittered strata), lhs (Latin hypercube) or independent")
        ->check(CLI::IsMember(samplerNames()));
    cmd_->add_option("--adaptive", adaptive_,
                     "Adaptive sampling, --spp being the average (path integrator only): "
                     "sequential (uniform quarter, then more samples to the pixels with the largest relative error; "
                     "BIASED: a pixel stops when its samples so far happen to agree, e.g. before it has seen a rare "
                     "bright value) or twostage (a pilot quarter only sets n_i ~ relative standard deviation, is "
                     "discarded, and fresh samples make the image: unbiased)")
        ->check(CLI::IsMember({"none", "sequential", "twostage"}));
    cmd_->add_option("--aov", aovs_,
                     "Extra output: variance = per-pixel variance of the pixel's mean luminance (grey image), "
                     "written next to each output as <stem>.variance.<ext>")
        ->check(CLI::IsMember({"variance"}));
    cmd_->add_option("-o,--output,--outfile", outputs_,
                     "Output image(s): .exr (float32), .png (sRGB 8-bit, clamped), .pfm; may be repeated. "
                     "Default: the scene's Film filename, relative to the current directory");
    cmd_->add_option("--crop,--cropwindow", crop_,
                     "Crop window x0 x1 y0 y1 (or x0,x1,y0,y1) in [0,1], y down, as pbrt-v4's --cropwindow")
        ->expected(4)
        ->allow_extra_args(false);
    cmd_->add_option("--pixelbounds", pixelBounds_,
                     "Render only pixels x0 <= x < x1, y0 <= y < y1 of the film, as pbrt-v4's --pixelbounds")
        ->expected(4)
        ->allow_extra_args(false);
    cmd_->add_option("--stats", statsFile_,
                     "Write the render statistics as JSON to this file; with no file (pbrt-v4's flag), print them "
                     "after the render");
    cmd_->add_flag("--stats-print", statsPrint_)->group("");  // `--stats` alone (normaliseArguments)
    cmd_->add_option("--checkpoint", checkpoint_,
                     "Write the film's exact sums to this file after a whole pass, every --checkpoint-every seconds "
                     "(atomically: a temporary file, flushed, renamed over it), to continue with --resume (path, "
                     "light and bdpt with uniform sampling)");
    cmd_->add_option("--checkpoint-every", checkpointEvery_,
                     "Seconds between checkpoints (default 60; 0: after every pass)")
        ->check(numberCheck(true));
    cmd_->add_option("--resume", resume_,
                     "Continue the render whose checkpoint this is (same scene file and settings, any number of "
                     "processes and threads): the image is the one an uninterrupted render gives; a higher --spp "
                     "than the checkpoint's continues it to more samples")
        ->check(CLI::ExistingFile);
    cmd_->add_option("--max-memory", maxMemory_,
                     "Memory limit for the film, images, meshes and strategy images, e.g. 512M, 8G, 1.5GiB "
                     "(binary units; default: 80% of physical memory, here " + formatBytes(memoryLimit()) +
                         "). An input that needs more fails before it is allocated, saying how much it needs")
        ->type_name("SIZE")
        ->check(plainCheck("a size such as 512M, 8G or 1.5GiB", "",
                           [](const std::string& s) { return parseByteSize(s).has_value(); }));
    // Metropolis (pssmlt, mmlt, mlt): each overrides the scene's Integrator parameter of the same meaning.
    cmd_->add_option("--chains", chains_,
                     "Metropolis (pssmlt, mmlt, mlt) only: number of Markov chains (overrides the scene's \"chains\"; default 1000)")
        ->check(countCheck());
    cmd_->add_option("--bootstrap", bootstrap_,
                     "Metropolis (pssmlt, mmlt, mlt) only: number of independent BDPT samples that estimate the normalisation b "
                     "and seed the chains (overrides \"bootstrapsamples\"; default 100000)")
        ->check(countCheck());
    cmd_->add_option("--large-step-probability", largeStepProbability_,
                     "Metropolis (pssmlt, mmlt) only: probability in [0, 1] that a mutation draws every random number afresh "
                     "(overrides \"largestepprobability\"; default 0.3)")
        ->check(probabilityCheck());
    cmd_->add_option("--camera-step-probability", cameraStepProbability_,
                     "Metropolis (pssmlt, mmlt) only: probability in [0, 1] that a small step moves only the camera "
                     "subpath and the connection, keeping the light subpath and the strategy (default 0.5; 0: every "
                     "small step moves every random number, as pbrt-v4's)")
        ->check(probabilityCheck());
    cmd_->add_option("--sigma", sigma_,
                     "Metropolis (pssmlt, mmlt) only: standard deviation (> 0) of a small step's perturbation of each random "
                     "number (overrides \"sigma\"; default 0.01)")
        ->check(numberCheck(false));
    cmd_->add_option("--strategy-pilot", strategyPilot_,
                     "mmlt only: fraction in [0, 1) of the bootstrap samples spent first on a pilot that learns how often "
                     "to choose each path depth and strategy and how to split the bootstrap among the depths (default 0.1; "
                     "0: no pilot, every depth and strategy equally)")
        ->check(probabilityCheck());
    cmd_->add_option("--two-stage", twoStage_,
                     "Metropolis (pssmlt, mmlt, mlt) only: two-stage MLT. F times the bootstrap's samples make a pilot "
                     "image, and the chains' target is the path's luminance over that image's brightness where the path "
                     "lands, so that dark parts of the image get about as many mutations as bright ones (default 1 for "
                     "pssmlt and mmlt, 0.25 for mlt; 0: off, the target is the luminance, as pbrt-v4's)")
        ->check(numberCheck(true));
    cmd_->add_option("--two-stage-black-level", twoStageBlackLevel_,
                     "two-stage MLT only: the pixel luminance L0 below which the chains spend their mutations as the "
                     "plain target does; the target's divisor is sqrt(B^2 + L0^2), which evens the error relative to "
                     "max(pixel, L0), as the relative MSE with the regulariser L0^2 measures it (default 0.1; 0: "
                     "relative error everywhere)")
        ->check(numberCheck(true));
    cmd_->add_option("--mlt-mutations", mltMutations_,
                     "mlt only: the mutations' weights, KEY=VALUE,... with keys bidirectional, lens-subpath, lens, "
                     "multi-chain, caustic, wavelengths (spectral mode) (default 1 each, wavelengths 0.25; a mutation is chosen among those that apply to the path in "
                     "proportion to its weight; 0 switches one off; bidirectional must stay > 0); also direct=N "
                     "(as --mlt-direct)");
    cmd_->add_option("--color", color_,
                     "spectral (default): each camera sample follows four wavelengths and the film's sensor (cie1931, "
                     "\"whitebalance\") makes colour, as pbrt-v4 renders; rgb: paths carry linear RGB (faster; saturated "
                     "colours, dispersion and white balance differ)")
        ->check(CLI::IsMember({"rgb", "spectral"}));
    cmd_->add_option("--mlt-direct", mltDirect_,
                     "mlt only: render the paths of at most one bounce (emission seen directly and direct lighting) "
                     "apart, with N samples per pixel of the path tracer, and leave them out of the chains (default 0: "
                     "the chains render every path)")
        ->check(CLI::NonNegativeNumber);
    cmd_->add_flag("--quiet", quiet_, "No progress bar or statistics on the terminal");

    const std::pair<const char*, std::vector<const char*>> groups[] = {
        {"Rendering", {"--spp", "--time", "--threads", "--seed", "--maxdepth", "--integrator", "--mis", "--sampler",
                       "--adaptive", "--color", "--max-memory"}},
        {"Output", {"--output", "--aov", "--crop", "--pixelbounds", "--stats", "--bdpt-strategies", "--quiet"}},
        {"Checkpoints", {"--checkpoint", "--checkpoint-every", "--resume"}},
        {"Metropolis (pssmlt, mmlt, mlt)",
         {"--chains", "--bootstrap", "--large-step-probability", "--camera-step-probability", "--sigma",
          "--strategy-pilot", "--two-stage", "--two-stage-black-level", "--mlt-mutations", "--mlt-direct"}}};
    for (const auto& [group, names] : groups)
        for (const char* name : names) cmd_->get_option(name)->group(group);
    refuseOptionsAsValues(cmd_);
}

void RenderCommand::load(Job& job) {
    const HeldWarnings inFileOrder;  // released when the scene is ready, or on an error
    if (!maxMemory_.empty()) setMemoryLimit(*parseByteSize(maxMemory_));  // validated by the option
    SceneDescription desc = parseSceneFile(scene_);
    std::unique_ptr<Scene>& scene = job.scene;
    scene = buildScene(desc, color_ == "spectral");
    RenderSettings& settings = scene->settings();
    if (spp_ > 0) settings.spp = spp_;
    if (seed_ >= 0) settings.seed = uint64_t(seed_);
    if (maxDepth_ >= 0) settings.maxDepth = maxDepth_;
    if (!integrator_.empty())
        settings.integrator = integrator_ == "volpath"     ? "path"
                              : integrator_ == "lightpath" ? "light"
                                                           : integrator_;
    if (!sampler_.empty()) settings.sampler = sampler_;
    settings.spectral = color_ == "spectral";
    if (strategyPilot_ >= 0) {
        if (settings.integrator != "mmlt")
            throw InputError("--strategy-pilot is a parameter of multiplexed MLT: it needs --integrator mmlt (the "
                             "integrator here is \"" + settings.integrator + "\")");
        if (strategyPilot_ >= 1) throw InputError("--strategy-pilot must be below 1 (the bootstrap proper needs samples)");
        settings.mltStrategyPilot = float(strategyPilot_);
    }
    if (!mltMutations_.empty()) {
        if (settings.integrator != "mlt")
            throw InputError("--mlt-mutations sets the mutations of Veach's MLT: it needs --integrator mlt (the "
                             "integrator here is \"" + settings.integrator + "\")");
        settings.mltMutations = mltMutations_;
    }
    if (mltDirect_ >= 0) {
        if (settings.integrator != "mlt")
            throw InputError("--mlt-direct renders direct lighting apart from Veach's MLT: it needs --integrator mlt (the "
                             "integrator here is \"" + settings.integrator + "\")");
        // Carried with the mutations' weights: mlt's own configuration.
        settings.mltMutations += (settings.mltMutations.empty() ? "direct=" : ",direct=") + std::to_string(mltDirect_);
    }
    if (settings.integrator == "mlt" && (largeStepProbability_ >= 0 || sigma_ > 0 || cameraStepProbability_ >= 0))
        throw InputError("--large-step-probability, --camera-step-probability and --sigma are parameters of the "
                         "primary-sample-space Metropolis integrators (pssmlt, mmlt); mlt's mutations change paths, "
                         "not random numbers");
    if (chains_ > 0 || bootstrap_ > 0 || largeStepProbability_ >= 0 || sigma_ > 0 || cameraStepProbability_ >= 0 ||
        twoStage_ >= 0 || twoStageBlackLevel_ >= 0) {
        if (settings.integrator != "pssmlt" && settings.integrator != "mmlt" && settings.integrator != "mlt")
            throw InputError("--chains, --bootstrap, --large-step-probability, --camera-step-probability, --sigma, "
                             "--two-stage and --two-stage-black-level are Metropolis parameters: "
                             "they need --integrator pssmlt, mmlt or mlt (the integrator here is \"" + settings.integrator +
                             "\")");
        if (chains_ > 0) settings.mltChains = chains_;
        if (bootstrap_ > 0) settings.mltBootstrapSamples = bootstrap_;
        if (largeStepProbability_ >= 0) settings.mltLargeStepProbability = float(largeStepProbability_);
        if (sigma_ > 0) settings.mltSigma = float(sigma_);
        if (cameraStepProbability_ >= 0) settings.mltCameraStepProbability = float(cameraStepProbability_);
        if (twoStage_ >= 0) settings.mltTwoStage = float(twoStage_);
        if (twoStageBlackLevel_ >= 0) {
            if (metropolisTwoStage(settings.integrator, settings.mltTwoStage) == 0)
                throw InputError("--two-stage-black-level needs two-stage MLT, which --two-stage 0 switches off");
            settings.mltTwoStageBlackLevel = float(twoStageBlackLevel_);
        }
    }
    const int W = scene->camera().params().xRes, H = scene->camera().params().yRes;
    if (!crop_.empty() && !pixelBounds_.empty())
        throw InputError("--crop and --pixelbounds both choose the pixels to render: give one");
    if (!crop_.empty()) {
        for (float c : crop_)
            if (!(c >= 0 && c <= 1)) {
                char text[32];
                std::snprintf(text, sizeof text, "%g", double(c));
                throw InputError(std::string("--crop: every value must lie in [0, 1], not ") + text);
            }
        if (!(crop_[0] < crop_[1]) || !(crop_[2] < crop_[3]))
            throw InputError("--crop x0 x1 y0 y1 needs x0 < x1 and y0 < y1");
        PixelBounds b = cropWindowToPixels(W, H, crop_.data());
        if (b.width() <= 0 || b.height() <= 0) throw InputError("--crop: the crop window holds no pixel");
        scene->setPixelBounds(b);
    }
    if (!pixelBounds_.empty()) {
        const std::vector<int>& p = pixelBounds_;
        if (p[0] < 0 || p[2] < 0 || p[1] > W || p[3] > H || p[0] >= p[1] || p[2] >= p[3])
            throw InputError("--pixelbounds x0 x1 y0 y1 needs 0 <= x0 < x1 <= " + std::to_string(W) +
                             " and 0 <= y0 < y1 <= " + std::to_string(H) + " (the film's resolution)");
        scene->setPixelBounds(PixelBounds{p[0], p[1], p[2], p[3]});
    }
    // pbrt-v4 warns too: a scene without emitters renders black.
    if (scene->lights().empty()) warning("the scene has no light source or emitting shape: the image will be black");
    job.outputs = outputs_;
    if (job.outputs.empty()) job.outputs.push_back(std::filesystem::path(settings.outputFile).filename().string());
    job.writeVariance = std::find(aovs_.begin(), aovs_.end(), "variance") != aovs_.end();
    std::unique_ptr<Integrator>& integrator = job.integrator;
    integrator = createIntegrator(settings.integrator, *scene, mis_);
    // A darker image with no word of why is a wrong answer (missingPaths says which light).
    if (const std::string why = missingPaths(*scene, settings.integrator); !why.empty())
        warning("integrator \"" + settings.integrator + "\" will render part of this scene's light black: " + why);
    if (const std::string why = inconsistentSurfaces(*scene, settings.integrator); !why.empty())
        warning("integrator \"" + settings.integrator + "\" may render some curves other than path tracing: " + why);
    const AdaptiveMode adaptive = parseAdaptiveMode(adaptive_);
    if (adaptive != AdaptiveMode::None && integrator->splats())
        throw InputError("--adaptive " + adaptive_ + " needs --integrator path: light tracing, BDPT and Metropolis "
                         "splat paths anywhere on the film, so a pixel's samples do not make its value");
    BDPTIntegrator*& bdpt = job.bdpt;
    if (!strategiesDir_.empty()) {
        bdpt = dynamic_cast<BDPTIntegrator*>(integrator.get());
        if (!bdpt) throw InputError("--bdpt-strategies needs --integrator bdpt (the scene asks for \"" +
                                    settings.integrator + "\")");
        bdpt->recordStrategies(std::min(settings.maxDepth, 5));  // checks their memory (use --crop if too much)
    }

    // Checkpoints: what must match to resume (the scene file's bytes and the options that shape
    // the image; not threads, processes or time), then the checkpoint resumed from, checked
    // before anything is rendered or written.
    if (checkpointEvery_ >= 0 && checkpoint_.empty()) throw InputError("--checkpoint-every needs --checkpoint FILE");
    if ((!checkpoint_.empty() || !resume_.empty()) && (adaptive != AdaptiveMode::None || bdpt))
        throw InputError(std::string(adaptive != AdaptiveMode::None ? "adaptive sampling (--adaptive)" : "--bdpt-strategies") +
                         " does not yet write or resume checkpoints: path, light and bdpt with uniform sampling and "
                         "the Metropolis integrators (pssmlt, mmlt, mlt) do");
    const PixelBounds& bounds = scene->pixelBounds();
    const bool checkpointing = !checkpoint_.empty() || !resume_.empty();
    nlohmann::json& checkpointSettings = job.checkpointSettings;
    checkpointSettings = {
        {"scene_file_hash", checkpointing ? fileHash(scene_) : ""},
        {"input_files", checkpointing ? inputFileHashes(scene_) : nlohmann::json::object()},
        {"integrator", settings.integrator},
        {"spp", settings.spp},
        {"seed", settings.seed},
        {"sampler", settings.sampler},
        {"maxdepth", settings.maxDepth},
        {"mis", mis_},
        {"resolution", {scene->camera().params().xRes, scene->camera().params().yRes}},
        {"pixels", {bounds.x0, bounds.x1, bounds.y0, bounds.y1}}};
    if (settings.spectral) checkpointSettings["color"] = "spectral";  // absent: RGB, as before the option existed
    // A Markov chain's course depends on every parameter of the chains and the bootstrap.
    if (settings.integrator == "pssmlt" || settings.integrator == "mmlt" || settings.integrator == "mlt") {
        checkpointSettings["chains"] = settings.mltChains;
        checkpointSettings["bootstrap"] = settings.mltBootstrapSamples;
        checkpointSettings["large_step_probability"] = settings.mltLargeStepProbability;
        checkpointSettings["sigma"] = settings.mltSigma;
        checkpointSettings["camera_step_probability"] = settings.mltCameraStepProbability;
        checkpointSettings["strategy_pilot"] = settings.mltStrategyPilot;
        checkpointSettings["mlt_mutations"] = settings.mltMutations;
        if (const double twoStage = metropolisTwoStage(settings.integrator, settings.mltTwoStage); twoStage > 0) {
            checkpointSettings["two_stage"] = twoStage;
            checkpointSettings["two_stage_black_level"] = settings.mltTwoStageBlackLevel;
        }
    }
    RenderOptions& opts = job.opts;
    opts.spp = settings.spp;
    opts.timeLimit = time_;
    const int cores = std::max(1, tbb::this_task_arena::max_concurrency());
    if (threads_ > cores)
        warning("--threads " + std::to_string(threads_) + ": this machine has " + std::to_string(cores) +
                " hardware threads; using " + std::to_string(cores));
    opts.threads = threads_ > 0 ? std::min(threads_, cores) : cores;
    opts.seed = settings.seed;
    opts.sampler = settings.sampler;
    opts.progress = !quiet_;
    opts.cancel = &gInterrupt;
    opts.adaptive = adaptive;
    // Only what will be shown or written: a quiet render without --stats or --aov variance
    // leaves the film's luminance moments out (bench/README.md, scene loading).
    opts.errorEstimate = !quiet_ || !statsFile_.empty();
    opts.varianceImage = job.writeVariance;
    opts.pixelSamples = false;
    checkRenderable(*scene, *integrator, opts);
}

void RenderCommand::checkRootsFiles(const Job& job, CheckpointState& resumed) {
    // Every file the render writes, by the words that name it: two alike, or one that is an
    // input, would lose one of them.
    std::vector<std::pair<std::string, std::string>> writes;
    for (const std::string& o : job.outputs) {
        checkWritable(o);
        writes.push_back({o, "-o " + o});
        if (job.writeVariance) writes.push_back({variancePath(o), "--aov variance's " + variancePath(o)});
    }
    if (!statsFile_.empty()) {
        checkFileWritable(statsFile_, "--stats");
        writes.push_back({statsFile_, "--stats " + statsFile_});
    }
    if (!checkpoint_.empty()) {
        checkFileWritable(checkpoint_, "--checkpoint");
        writes.push_back({checkpoint_, "--checkpoint " + checkpoint_});
    }
    if (job.bdpt) {
        std::error_code ec;
        std::filesystem::create_directories(strategiesDir_, ec);
        if (ec) throw InputError("--bdpt-strategies: cannot create \"" + strategiesDir_ + "\": " + ec.message());
        checkWritable((std::filesystem::path(strategiesDir_) / "s0_t2.exr").string());
    }
    if (!resume_.empty()) resumed = readCheckpoint(resume_, job.checkpointSettings);
    namespace fs = std::filesystem;
    auto same = [](const std::string& a, const std::string& b) {
        std::error_code ec;
        return fs::weakly_canonical(fs::absolute(a, ec), ec) == fs::weakly_canonical(fs::absolute(b, ec), ec);
    };
    for (size_t i = 0; i < writes.size(); ++i) {
        for (size_t k = i + 1; k < writes.size(); ++k)
            if (same(writes[i].first, writes[k].first))
                throw InputError(writes[i].second + " and " + writes[k].second + " name the same file");
        if (same(writes[i].first, scene_))
            throw InputError(writes[i].second + " would write over the scene file");
        // --resume F --checkpoint F continues and keeps saving: F is read before it is written.
        if (!resume_.empty() && same(writes[i].first, resume_) && writes[i].second.rfind("--checkpoint", 0) != 0)
            throw InputError(writes[i].second + " would write over the checkpoint it resumes");
    }
}

int RenderCommand::run() {
    // Input errors are met by every process alike (the same files and options): all stop
    // together at this point, rank 0 reporting (distributed::failedEverywhere).
    Job job;
    std::string error;
    bool failed = false;
    try {
        load(job);
    } catch (const InputError& e) {
        failed = true;
        error = e.what();
    }
    if (distributed::failedEverywhere(failed, error, kExitBadInput)) throw distributed::JobInputError(error);
    Scene* scene = job.scene.get();
    RenderSettings& settings = scene->settings();
    const std::vector<std::string>& outputs = job.outputs;
    const bool writeVariance = job.writeVariance;
    Integrator* integrator = job.integrator.get();
    BDPTIntegrator* bdpt = job.bdpt;
    const nlohmann::json& checkpointSettings = job.checkpointSettings;
    const bool root = distributed::isRoot();
    CheckpointState resumed;
    {
        // Rank 0 alone checks what it alone writes and reads (the others need not see its file
        // system): its refusal is the job's, raised by every process.
        std::string refusal;
        if (root) {
            try {
                checkRootsFiles(job, resumed);
            } catch (const InputError& e) {
                refusal = e.what();
            }
        }
        distributed::refuseTogether(!refusal.empty(), refusal);
    }
    if (!resume_.empty()) {
        // Rank 0 says where the checkpoint it read stands.
        distributed::Purpose purpose("checkpoint");
        std::vector<int64_t> where{0, 1, 0, 0, 0};
        if (root)
            where = {resumed.samplesPerPixel, resumed.passSize, int64_t(resumed.partial.size()), resumed.spp,
                     int64_t(resumed.sampleSets.size())};
        distributed::broadcastFromRoot(where);
        resumed.samplesPerPixel = int(where[0]);
        resumed.passSize = int(where[1]);
        resumed.partial.resize(size_t(where[2]));
        resumed.spp = int(where[3]);
        std::vector<int64_t> sets(resumed.sampleSets.begin(), resumed.sampleSets.end());
        sets.resize(size_t(where[4]));
        distributed::broadcastFromRoot(sets);
        resumed.sampleSets.assign(sets.begin(), sets.end());
        distributed::broadcastFromRoot(resumed.partial);
        // A raised --spp: the new samples are a set of their own (RenderOptions::sampleSets),
        // which the checkpoints this render writes record.
        job.opts.sampleSets = resumed.sampleSets;
        if (job.opts.spp > resumed.spp) job.opts.sampleSets.push_back(resumed.spp);
        if (!job.opts.sampleSets.empty()) job.checkpointSettings["sample_sets"] = job.opts.sampleSets;
    }

    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);

    RenderOptions& opts = job.opts;
    if (!resume_.empty()) opts.resume = &resumed;
    if (!checkpoint_.empty()) {
        opts.checkpointEvery = checkpointEvery_ >= 0 ? checkpointEvery_ : 60;
        opts.checkpoint = [&](const CheckpointState& s) { writeCheckpoint(checkpoint_, checkpointSettings, s); };
    }
    RenderResult r = render(*scene, *integrator, opts);
    // A signal to any process interrupted them all (each stops at the same pass boundary).
    bool interrupted = false;
    {
        distributed::Purpose purpose("stop decisions");
        interrupted = distributed::anyOf(gInterrupt.load());
    }
    if (bdpt) bdpt->strategyImages()->sumToRoot();
    gatherWarnings();
    if (!root) return interrupted ? kExitInterrupted : kExitOk;
    // The statistics count every collective of the render, these last ones included.
    r.distributed.reductionBytes = distributed::traffic().bytes;
    r.distributed.reductionSeconds = distributed::traffic().seconds;
    nlohmann::json byPurpose = nlohmann::json::object();
    for (const auto& [purpose, t] : distributed::trafficByPurpose())
        byPurpose[purpose] = {{"bytes", t.bytes}, {"seconds", t.seconds}};

    // A crop keeps its place in the film (the EXR's data window inside its display window).
    const PixelBounds& pb = scene->pixelBounds();
    const int filmW = scene->camera().params().xRes, filmH = scene->camera().params().yRes;
    if (pb.width() != filmW || pb.height() != filmH)
        for (Image* img : {&r.image, &r.variance}) {
            img->filmWidth = filmW;
            img->filmHeight = filmH;
            img->x0 = pb.x0;
            img->y0 = pb.y0;
        }
    for (const std::string& o : outputs) {
        writeImage(o, r.image);
        if (writeVariance) writeImage(variancePath(o), r.variance);
    }
    if (bdpt)
        for (const auto& [name, image] : bdpt->strategyImages()->images(r.lightPaths))
            writeImage((std::filesystem::path(strategiesDir_) / (name + ".exr")).string(), image);

    double secs = std::max(r.seconds, 1e-9);
    // A variance needs two samples of a pixel (or two half-buffers): below that it is unknown,
    // not zero. After --resume the image's variance covers the earlier runs' samples too, and
    // this run's time alone would overstate the efficiency 1/(V T): it is not given.
    const bool noiseKnown = r.meanSpp >= 2;
    const bool resumedRun = r.resumedSpp > 0;
    const bool efficiencyKnown = noiseKnown && !resumedRun && std::isfinite(r.efficiency);
    uint64_t rays = r.stats.rays + r.stats.shadowRays;
    // Rates are this run's work over this run's time (after --resume, the totals are not).
    const PathStats run = resume_.empty() ? r.stats : r.stats.since(resumed.stats);
    const double runRays = double(run.rays + run.shadowRays);
    nlohmann::json stats = {
        {"scene", scene_},
        {"outputs", outputs},
        {"integrator", settings.integrator},
        {"color", settings.spectral ? "spectral" : "rgb"},
        {"sampler", settings.sampler},
        {"adaptive", adaptive_.empty() ? "none" : adaptive_},
        {"resolution", {scene->camera().params().xRes, scene->camera().params().yRes}},
        {"pixels", scene->pixelBounds().area()},
        {"threads", job.opts.threads},
        {"ranks", r.distributed.ranks},
        {"rank_samples", r.distributed.rankSamples},
        {"rank_seconds", r.distributed.rankSeconds},
        {"reduction_bytes", r.distributed.reductionBytes},
        {"reduction_seconds", r.distributed.reductionSeconds},
        {"reduction_by_purpose", byPurpose},
        {"seed", settings.seed},
        {"maxdepth", settings.maxDepth},
        {"wall_time_s", r.seconds},
        {"spp_target", r.targetSpp},
        {"spp_mean", r.meanSpp},
        {"stopped_early", r.stoppedEarly},
        {"interrupted", interrupted},
        {"resumed_spp", r.resumedSpp},
        {"checkpoints", r.checkpoints},
        {"camera_paths", r.stats.cameraPaths},
        {"camera_paths_per_s", double(run.cameraPaths) / secs},
        {"light_paths", r.stats.lightPaths},
        {"rays", rays},
        {"closest_hit_rays", r.stats.rays},
        {"shadow_rays", r.stats.shadowRays},
        {"rays_per_s", runRays / secs},
        {"mean_pixel_variance", noiseKnown ? nlohmann::json(r.error.meanVariance) : nlohmann::json()},
        {"mean_relative_variance", noiseKnown ? nlohmann::json(r.error.meanRelativeVariance) : nlohmann::json()},
        {"efficiency", efficiencyKnown ? nlohmann::json(r.efficiency) : nlohmann::json()},
        {"nonfinite_guarded", r.stats.guarded},
        {"nonfinite_samples_rejected", r.rejectedSamples},
        {"warnings", warningCount()},
        {"memory_limit_bytes", memoryLimit()},
    };
    const MetropolisStats& ms = r.metropolis;
    // Veach's mlt has no large and small steps in primary sample space: those fields are
    // pssmlt's and mmlt's alone.
    const bool primarySample = settings.integrator != "mlt";
    if (ms.present) {
        stats["metropolis"] = {
            {"b", ms.b},
            {"bootstrap_samples", ms.bootstrapSamples},
            {"pilot_samples", ms.pilotSamples},
            {"two_stage_samples", ms.twoStageSamples},
            {"chains", ms.chains},
            {"mutations", ms.mutations},
            {"acceptance_rate", ms.acceptanceRate()},
            {"invalid_proposals", ms.invalidProposals},
            {"b_relative_error", ms.bRelativeError},
            {"rank_mutations", ms.rankMutations},
            {"rank_acceptance_rates", ms.rankAcceptance},
        };
        if (primarySample) {
            nlohmann::json& m = stats["metropolis"];
            m["large_step_probability"] = settings.mltLargeStepProbability;
            m["sigma"] = settings.mltSigma;
            m["camera_step_probability"] = settings.mltCameraStepProbability;
            m["large_steps"] = ms.proposedLarge;
            m["large_step_acceptance_rate"] = MetropolisStats::rate(ms.acceptedLarge, ms.proposedLarge);
            m["small_steps"] = ms.proposedSmall;
            m["small_step_acceptance_rate"] = MetropolisStats::rate(ms.acceptedSmall, ms.proposedSmall);
        }
    }
    if (ms.present) {
        // Per path depth: its share of the image and, for mmlt, its proposals' acceptance.
        nlohmann::json depths = nlohmann::json::array();
        for (size_t d = 0; d < ms.depths.size(); ++d) {
            nlohmann::json e = {{"depth", d}, {"share", ms.depths[d].share}};
            if (ms.multiplexed) {
                e["choice_probability"] = ms.depths[d].chosen;
                e["bootstrap_samples"] = ms.depths[d].bootstrapSamples;
                e["proposals"] = ms.depths[d].proposed;
                e["acceptance_rate"] = MetropolisStats::rate(ms.depths[d].accepted, ms.depths[d].proposed);
            }
            depths.push_back(e);
        }
        stats["metropolis"]["depths"] = depths;
        nlohmann::json kinds = nlohmann::json::array();
        for (const MetropolisStats::Kind& k : ms.kinds)
            kinds.push_back({{"mutation", k.name},
                             {"proposed", k.proposed},
                             {"failed", k.failed},
                             {"accepted", k.accepted},
                             {"acceptance_rate", MetropolisStats::rate(k.accepted, k.proposed)}});
        stats["metropolis"]["mutations_by_kind"] = kinds;
    }
    // Film "maxcomponentvalue": a biased image, said where the numbers are read.
    const bool clamped = std::isfinite(settings.maxComponentValue);
    constexpr const char* kClampNote = "biased: energy is lost where the clamp acts";
    if (clamped) stats["max_component_value"] = {{"value", settings.maxComponentValue}, {"note", kClampNote}};
    if (statsPrint_) std::printf("%s\n", stats.dump(2).c_str());
    if (!statsFile_.empty()) {
        std::ofstream f(statsFile_);
        if (!f) throw InputError("--stats: cannot write \"" + statsFile_ + "\"");
        f << stats.dump(2) << "\n";
    }
    if (!quiet_) {
        std::printf("%s\n", summaryLine(settings, job.opts.threads).c_str());
        std::printf("wrote %s", outputs[0].c_str());
        for (size_t i = 1; i < outputs.size(); ++i) std::printf(", %s", outputs[i].c_str());
        std::printf("\n");
        // Light tracing traces no camera paths: its rate is of light paths.
        const bool lightOnly = r.stats.cameraPaths == 0 && r.stats.lightPaths > 0;
        // After --resume: the totals are the whole render's, the rates this run's over its time.
        char thisRun[96] = "";
        if (resumedRun)
            std::snprintf(thisRun, sizeof thisRun, ", %.1f of them this run, %d resumed", r.meanSpp - r.resumedSpp,
                          r.resumedSpp);
        std::printf("time %.3f s | %.1f spp (target %d%s) | %.3g %s paths/s | %.3g rays (%.3g closest, %.3g shadow) | "
                    "%.3g rays/s | non-finite: %llu guarded, %lld rejected\n",
                    r.seconds, r.meanSpp, r.targetSpp, thisRun,
                    double(lightOnly ? run.lightPaths : run.cameraPaths) / secs, lightOnly ? "light" : "camera",
                    double(rays), double(r.stats.rays), double(r.stats.shadowRays), runRays / secs,
                    (unsigned long long)r.stats.guarded, r.rejectedSamples);
        if (efficiencyKnown)
            std::printf("noise estimate: mean relative variance %.3g, efficiency 1/(V T) %.3g\n",
                        r.error.meanRelativeVariance, r.efficiency);
        else if (noiseKnown)
            std::printf("noise estimate: mean relative variance %.3g, efficiency n/a (%s)\n", r.error.meanRelativeVariance,
                        resumedRun ? "resumed: the variance is of every run's samples, the time of this run's"
                                   : "no variance");
        else
            std::printf("noise estimate: n/a (fewer than 2 samples per pixel)\n");
        if (clamped)
            std::printf("clamp: Film \"maxcomponentvalue\" %g (%s)\n", double(settings.maxComponentValue), kClampNote);
        if (r.distributed.ranks > 1)
            std::printf("%d processes (MPI) | rank 0's collectives: %.3g MB in %.3f s\n", r.distributed.ranks,
                        r.distributed.reductionBytes / 1e6, r.distributed.reductionSeconds);
        if (ms.present) {
            std::printf("metropolis: b %.4g | %d chains | %lld mutations | acceptance %.3f", ms.b, ms.chains,
                        ms.mutations, ms.acceptanceRate());
            if (primarySample)
                std::printf(" (large steps %.3f, small steps %.3f)", MetropolisStats::rate(ms.acceptedLarge, ms.proposedLarge),
                            MetropolisStats::rate(ms.acceptedSmall, ms.proposedSmall));
            std::printf(" | %lld invalid proposals\n", ms.invalidProposals);
            std::printf("metropolis: b relative error %.3g", ms.bRelativeError);
            // The depths up to the last whose share of the image shows at three digits (a
            // maxdepth of 100 would print a hundred zeros per list).
            size_t shown = ms.depths.size();
            while (shown > 1 && ms.depths[shown - 1].share < 5e-4) --shown;
            const std::span<const MetropolisStats::Depth> depths(ms.depths.data(), shown);
            if (!depths.empty()) std::printf(" | per depth: share");
            for (const MetropolisStats::Depth& d : depths) std::printf(" %.3f", d.share);
            if (ms.multiplexed) {
                std::printf(" | chosen");
                for (const MetropolisStats::Depth& d : depths) std::printf(" %.3f", d.chosen);
                std::printf(" | acceptance");
                for (const MetropolisStats::Depth& d : depths)
                    std::printf(" %.3f", MetropolisStats::rate(d.accepted, d.proposed));
            }
            if (shown < ms.depths.size())
                std::printf(" | %zu deeper depths, each below 0.0005 of the image (--stats lists them)", ms.depths.size() - shown);
            std::printf("\n");
            for (const MetropolisStats::Kind& k : ms.kinds)
                std::printf("metropolis: %s mutation: %lld proposed, %lld failed, acceptance %.3f\n", k.name.c_str(),
                            k.proposed, k.failed, MetropolisStats::rate(k.accepted, k.proposed));
        }
        if (!resume_.empty()) {
            std::printf("resumed from %s", resume_.c_str());
            if (r.resumedSpp > 0) std::printf(" at %d spp", r.resumedSpp);
            if (resumed.spp < opts.spp) std::printf("; --spp raised from its %d to %d", resumed.spp, opts.spp);
            std::printf("\n");
        }
        if (r.checkpoints > 0)
            std::printf("checkpoint %s (%d written) holds %s; --resume %s continues it, to a higher --spp too\n",
                        checkpoint_.c_str(), r.checkpoints, r.checkpointKept.c_str(), checkpoint_.c_str());
        else if (!checkpoint_.empty())
            std::printf("no checkpoint written to %s: the render stopped before it had anything to keep\n",
                        checkpoint_.c_str());
        if (r.stoppedEarly) std::printf("stopped early: %s\n", interrupted ? "interrupted" : "time budget reached");
    }
    return interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace ps
