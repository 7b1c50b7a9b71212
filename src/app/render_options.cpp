#include "app/render_options.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <tbb/task_arena.h>

#include "mc/mis.h"
#include "mc/sampler.h"
#include "render/distributed.h"
#include "transport/bdpt.h"
#include "transport/coverage.h"
#include "transport/integrator.h"
#include "transport/scrambled_sets.h"
#include "util/error.h"
#include "util/memory_limit.h"

namespace ps {

namespace {

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

}  // namespace

bool RenderArgs::varianceImage() const { return std::find(aovs.begin(), aovs.end(), "variance") != aovs.end(); }

void addRenderOptions(CLI::App* cmd, RenderArgs& a) {
    cmd->add_option("--spp", a.spp, "Samples per pixel (overrides the scene's Sampler pixelsamples)")->check(wholeCheck(1));
    cmd->add_option("--time", a.time, "Time budget in seconds; the image so far is written when it runs out")
        ->check(numberCheck(false));
    cmd->add_option("--threads,--nthreads", a.threads,
                     "Worker threads (default: all cores; more than the machine has are cut to that)")
        ->check(wholeCheck(0));
    cmd->add_option("--seed", a.seed, "Random seed (overrides the scene's; the same seed gives the same image)")
        ->check(wholeCheck(0, 9223372036854775807LL));
    cmd->add_option("--maxdepth", a.maxDepth, "Maximum number of scattering events (overrides the scene's)")
        ->check(wholeCheck(0));
    cmd->add_option("--integrator", a.integrator,
                     "Integrator: path (path tracing with MIS), light (light tracing: particles from the lights "
                     "splatted through the lens), bdpt (bidirectional path tracing, every strategy with MIS), pssmlt "
                     "(primary-sample-space Metropolis light transport over BDPT), mmlt (multiplexed Metropolis: the "
                     "chains also choose the path depth and one BDPT strategy), mlt (Veach's Metropolis light transport: "
                     "chains over paths themselves, changed by path-space mutations); for the Metropolis integrators "
                     "--spp sets the mutations per pixel. pbrt names volpath and lightpath map to path and light (a "
                     "scene's Integrator \"mlt\" is pbrt-v4's multiplexed MLT: mmlt)")
        ->check(CLI::IsMember({"path", "volpath", "light", "lightpath", "bdpt", "pssmlt", "mmlt", "mlt"}));
    cmd->add_option("--bdpt-strategies", a.strategiesDir,
                     "With --integrator bdpt: also write, into this directory, one EXR per strategy (s light "
                     "vertices, t camera vertices) up to the path depth --maxdepth, MIS-weighted (s<S>_t<T>.exr) and "
                     "unweighted (s<S>_t<T>_unweighted.exr); the weighted ones sum to the image");
    cmd->add_option("--mis", a.mis,
                    "MIS heuristic of path, bdpt, pssmlt and mmlt (thesis ch. 9): power[:BETA] (default power:2), "
                    "balance, cutoff[:ALPHA] (default 0.1), maximum, none (uniform)")
        ->check([](const std::string& v) {
            try {
                parseMisWeighting(v);
                return std::string();
            } catch (const InputError& e) {
                return std::string(e.what());
            }
        });
    cmd->add_option_function<std::string>(
           "--light-paths",
           [&a](const std::string& v) {
               a.lightPathsAuto = v == "auto";
               if (!a.lightPathsAuto) a.lightPaths = std::strtof(v.c_str(), nullptr);
           },
           "With --integrator bdpt: light subpaths per camera sample, in (0, 1] (default 1), or auto. Below 1, "
           "a sample is a BDPT sample with this probability and a path tracer's otherwise "
           "(docs/integrators.md): path tracing's cost where light subpaths add little, as in "
           "directly lit scenes. auto: 1 or a small share, whichever a pilot of each finds more efficient")
        ->check([](const std::string& v) {
            if (v == "auto") return std::string();
            char* end = nullptr;
            const float f = std::strtof(v.c_str(), &end);
            return !v.empty() && *end == '\0' && f > 0 && f <= 1 ? std::string()
                                                                 : "expected a share in (0, 1] or auto, got \"" + v + "\"";
        });
    cmd->add_option("--shadow-roulette", a.shadowRoulette,
                    "Russian roulette on shadow rays (thesis 10.3.4; path, light, bdpt): a connection whose "
                    "unoccluded contribution C is below tau = this share of the image's mean so far traces its "
                    "shadow ray with probability C / tau (docs/shadow-roulette.md). 0 (default): every shadow ray")
        ->check([](const std::string& v) {
            char* end = nullptr;
            const float f = std::strtof(v.c_str(), &end);
            return !v.empty() && *end == '\0' && f >= 0 && f <= 100 ? std::string()
                                                                    : "expected a share in [0, 100], got \"" + v + "\"";
        });
    cmd->add_option("--light-samples", a.lightSamples,
                    "With --integrator path: light samples per path vertex (next-event estimation split N "
                    "ways, each counting 1/N; the MIS weights count the light technique N times). Default 1; "
                    "docs/strategy-figures.md measures when more pay")
        ->check(wholeCheck(1, 1024));
    cmd->add_option("--sampler", a.sampler,
                     "Sample placement per pixel: sobol (default; Owen-scrambled Sobol, padded), zsobol (Sobol in "
                     "Morton order over the image: blue-noise error), halton (Owen-scrambled Halton), orthogonal "
                     "(randomised orthogonal arrays), stratified (jittered strata), lhs (Latin hypercube) or independent")
        ->check(CLI::IsMember(samplerNames()));
    cmd->add_option("--adaptive", a.adaptive,
                     "Adaptive sampling, --spp being the average (path integrator only): "
                     "sequential (uniform quarter, then more samples to the pixels with the largest relative error; "
                     "BIASED: a pixel stops when its samples so far happen to agree, e.g. before it has seen a rare "
                     "bright value) or twostage (a pilot quarter only sets n_i ~ relative standard deviation, is "
                     "discarded, and fresh samples make the image: unbiased)")
        ->check(CLI::IsMember({"none", "sequential", "twostage"}));
    cmd->add_option("--aov", a.aovs,
                     "Extra output: variance = per-pixel variance of the pixel's mean luminance (grey image), "
                     "written next to each output as <stem>.variance.<ext>")
        ->check(CLI::IsMember({"variance"}));
    cmd->add_option("-o,--output,--outfile", a.outputs,
                     "Output image(s): .exr (float32), .png (sRGB 8-bit, clamped), .pfm; may be repeated. "
                     "Default: the scene's Film filename, relative to the current directory");
    cmd->add_option("--crop,--cropwindow", a.crop,
                     "Crop window x0 x1 y0 y1 (or x0,x1,y0,y1) in [0,1], y down, as pbrt-v4's --cropwindow")
        ->expected(4)
        ->allow_extra_args(false);
    cmd->add_option("--pixelbounds", a.pixelBounds,
                     "Render only pixels x0 <= x < x1, y0 <= y < y1 of the film, as pbrt-v4's --pixelbounds")
        ->expected(4)
        ->allow_extra_args(false);
    cmd->add_option("--stats", a.statsFile,
                     "Write the render statistics as JSON to this file; with no file (pbrt-v4's flag), print them "
                     "after the render");
    cmd->add_flag("--stats-print", a.statsPrint)->group("");  // `--stats` alone (normaliseArguments)
    cmd->add_option("--checkpoint", a.checkpoint,
                     "Write the film's exact sums to this file after a whole pass, every --checkpoint-every seconds "
                     "(atomically: a temporary file, flushed, renamed over it), to continue with --resume (path, "
                     "light and bdpt with uniform sampling)");
    cmd->add_option("--checkpoint-every", a.checkpointEvery,
                     "Seconds between checkpoints (default 60; 0: after every pass)")
        ->check(numberCheck(true));
    cmd->add_option("--resume", a.resume,
                     "Continue the render whose checkpoint this is (same scene file and settings, any number of "
                     "processes and threads): the image is the one an uninterrupted render gives; a higher --spp "
                     "than the checkpoint's continues it to more samples")
        ->check(CLI::ExistingFile);
    cmd->add_option("--max-memory", a.maxMemory,
                     "Memory limit for the film, images, meshes and strategy images, e.g. 512M, 8G, 1.5GiB "
                     "(binary units; default: 80% of physical memory, here " + formatBytes(memoryLimit()) +
                         "). An input that needs more fails before it is allocated, saying how much it needs")
        ->type_name("SIZE")
        ->check(plainCheck("a size such as 512M, 8G or 1.5GiB", "",
                           [](const std::string& s) { return parseByteSize(s).has_value(); }));
    // Metropolis (pssmlt, mmlt, mlt): each overrides the scene's Integrator parameter of the same meaning.
    cmd->add_option("--chains", a.chains,
                     "Metropolis (pssmlt, mmlt, mlt) only: number of Markov chains (overrides the scene's \"chains\"; default 1000)")
        ->check(countCheck());
    cmd->add_option("--bootstrap", a.bootstrap,
                     "Metropolis (pssmlt, mmlt, mlt) only: number of BDPT samples (their first numbers stratified over the set) "
                     "that estimate the normalisation b and seed the chains (overrides \"bootstrapsamples\"; default 100000)")
        ->check(countCheck());
    cmd->add_option("--large-step-probability", a.largeStepProbability,
                     "Metropolis (pssmlt, mmlt) only: probability in [0, 1] that a mutation draws every random number afresh "
                     "(overrides \"largestepprobability\"; default 0.3)")
        ->check(probabilityCheck());
    cmd->add_option("--camera-step-probability", a.cameraStepProbability,
                     "Metropolis (pssmlt, mmlt) only: probability in [0, 1] that a small step moves only the camera "
                     "subpath and the connection, keeping the light subpath and the strategy (default 0.5; 0: every "
                     "small step moves every random number, as pbrt-v4's)")
        ->check(probabilityCheck());
    cmd->add_option("--sigma", a.sigma,
                     "Metropolis (pssmlt, mmlt) only: standard deviation (> 0) of a small step's perturbation of each random "
                     "number (overrides \"sigma\"; default 0.01)")
        ->check(numberCheck(false));
    cmd->add_option("--strategy-pilot", a.strategyPilot,
                     "mmlt only: fraction in [0, 1) of the bootstrap samples spent first on a pilot that learns how often "
                     "to choose each path depth and strategy and how to split the bootstrap among the depths (default 0.1; "
                     "0: no pilot, every depth and strategy equally)")
        ->check(probabilityCheck());
    cmd->add_option("--two-stage", a.twoStage,
                     "Metropolis (pssmlt, mmlt, mlt) only: two-stage MLT. F times the bootstrap's samples make a pilot "
                     "image, and the chains' target is the path's luminance over that image's brightness where the path "
                     "lands, so that dark parts of the image get about as many mutations as bright ones (default 1 for "
                     "pssmlt and mmlt, 0.25 for mlt; 0: off, the target is the luminance, as pbrt-v4's)")
        ->check(numberCheck(true));
    cmd->add_option("--two-stage-black-level", a.twoStageBlackLevel,
                     "two-stage MLT only: the pixel luminance L0 below which the chains spend their mutations as the "
                     "plain target does; the target's divisor is sqrt(B^2 + L0^2), which evens the error relative to "
                     "max(pixel, L0), as the relative MSE with the regulariser L0^2 measures it (default 0.1; 0: "
                     "relative error everywhere)")
        ->check(numberCheck(true));
    cmd->add_option("--mlt-mutations", a.mltMutations,
                     "mlt only: the mutations' weights, KEY=VALUE,... with keys bidirectional, lens-subpath, lens, "
                     "multi-chain, caustic, wavelengths (spectral mode) (default 1 each, wavelengths 0.25; a mutation is chosen among those that apply to the path in "
                     "proportion to its weight; 0 switches one off; bidirectional must stay > 0); also direct=N "
                     "(as --mlt-direct)");
    cmd->add_option("--color", a.color,
                     "spectral (default): each camera sample follows four wavelengths and the film's sensor (cie1931, "
                     "\"whitebalance\") makes colour, as pbrt-v4 renders; rgb: paths carry linear RGB (faster; saturated "
                     "colours, dispersion and white balance differ)")
        ->check(CLI::IsMember({"rgb", "spectral"}));
    cmd->add_option("--mlt-direct", a.mltDirect,
                     "mlt only: render the paths of at most one bounce (emission seen directly and direct lighting) "
                     "apart, with N samples per pixel of the path tracer, and leave them out of the chains (default 0: "
                     "the chains render every path)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("--quiet", a.quiet, "No progress bar or statistics on the terminal");

    const std::pair<const char*, std::vector<const char*>> groups[] = {
        {"Rendering", {"--spp", "--time", "--threads", "--seed", "--maxdepth", "--integrator", "--mis", "--light-paths", "--shadow-roulette", "--sampler",
                       "--adaptive", "--color", "--max-memory"}},
        {"Output", {"--output", "--aov", "--crop", "--pixelbounds", "--stats", "--bdpt-strategies", "--quiet"}},
        {"Checkpoints", {"--checkpoint", "--checkpoint-every", "--resume"}},
        {"Metropolis (pssmlt, mmlt, mlt)",
         {"--chains", "--bootstrap", "--large-step-probability", "--camera-step-probability", "--sigma",
          "--strategy-pilot", "--two-stage", "--two-stage-black-level", "--mlt-mutations", "--mlt-direct"}}};
    for (const auto& [group, names] : groups)
        for (const char* name : names) cmd->get_option(name)->group(group);
}

void configureRender(Scene& scene, const RenderArgs& a, RenderSetup& setup) {
    RenderSettings& settings = scene.settings();
    if (a.spp > 0) settings.spp = a.spp;
    if (a.seed >= 0) settings.seed = uint64_t(a.seed);
    if (a.maxDepth >= 0) settings.maxDepth = a.maxDepth;
    if (!a.integrator.empty())
        settings.integrator = a.integrator == "volpath"     ? "path"
                              : a.integrator == "lightpath" ? "light"
                                                           : a.integrator;
    if (!a.sampler.empty()) settings.sampler = a.sampler;
    settings.spectral = a.color == "spectral";
    if (a.strategyPilot >= 0) {
        if (settings.integrator != "mmlt")
            throw InputError("--strategy-pilot is a parameter of multiplexed MLT: it needs --integrator mmlt (the "
                             "integrator here is \"" + settings.integrator + "\")");
        if (a.strategyPilot >= 1) throw InputError("--strategy-pilot must be below 1 (the bootstrap proper needs samples)");
        settings.mltStrategyPilot = float(a.strategyPilot);
    }
    if (!a.mltMutations.empty()) {
        if (settings.integrator != "mlt")
            throw InputError("--mlt-mutations sets the mutations of Veach's MLT: it needs --integrator mlt (the "
                             "integrator here is \"" + settings.integrator + "\")");
        settings.mltMutations = a.mltMutations;
    }
    if (a.mltDirect >= 0) {
        if (settings.integrator != "mlt")
            throw InputError("--mlt-direct renders direct lighting apart from Veach's MLT: it needs --integrator mlt (the "
                             "integrator here is \"" + settings.integrator + "\")");
        // Carried with the mutations' weights: mlt's own configuration.
        settings.mltMutations += (settings.mltMutations.empty() ? "direct=" : ",direct=") + std::to_string(a.mltDirect);
    }
    if (settings.integrator == "mlt" && (a.largeStepProbability >= 0 || a.sigma > 0 || a.cameraStepProbability >= 0))
        throw InputError("--large-step-probability, --camera-step-probability and --sigma are parameters of the "
                         "primary-sample-space Metropolis integrators (pssmlt, mmlt); mlt's mutations change paths, "
                         "not random numbers");
    if (a.chains > 0 || a.bootstrap > 0 || a.largeStepProbability >= 0 || a.sigma > 0 || a.cameraStepProbability >= 0 ||
        a.twoStage >= 0 || a.twoStageBlackLevel >= 0) {
        if (settings.integrator != "pssmlt" && settings.integrator != "mmlt" && settings.integrator != "mlt")
            throw InputError("--chains, --bootstrap, --large-step-probability, --camera-step-probability, --sigma, "
                             "--two-stage and --two-stage-black-level are Metropolis parameters: "
                             "they need --integrator pssmlt, mmlt or mlt (the integrator here is \"" + settings.integrator +
                             "\")");
        if (a.chains > 0) settings.mltChains = a.chains;
        if (a.bootstrap > 0) settings.mltBootstrapSamples = a.bootstrap;
        if (a.largeStepProbability >= 0) settings.mltLargeStepProbability = float(a.largeStepProbability);
        if (a.sigma > 0) settings.mltSigma = float(a.sigma);
        if (a.cameraStepProbability >= 0) settings.mltCameraStepProbability = float(a.cameraStepProbability);
        if (a.twoStage >= 0) settings.mltTwoStage = float(a.twoStage);
        if (a.twoStageBlackLevel >= 0) {
            if (metropolisTwoStage(settings.integrator, settings.mltTwoStage) == 0)
                throw InputError("--two-stage-black-level needs two-stage MLT, which --two-stage 0 switches off");
            settings.mltTwoStageBlackLevel = float(a.twoStageBlackLevel);
        }
    }
    const int W = scene.camera().params().xRes, H = scene.camera().params().yRes;
    if (!a.crop.empty() && !a.pixelBounds.empty())
        throw InputError("--crop and --pixelbounds both choose the pixels to render: give one");
    if (!a.crop.empty()) {
        for (float c : a.crop)
            if (!(c >= 0 && c <= 1)) {
                char text[32];
                std::snprintf(text, sizeof text, "%g", double(c));
                throw InputError(std::string("--crop: every value must lie in [0, 1], not ") + text);
            }
        if (!(a.crop[0] < a.crop[1]) || !(a.crop[2] < a.crop[3]))
            throw InputError("--crop x0 x1 y0 y1 needs x0 < x1 and y0 < y1");
        PixelBounds b = cropWindowToPixels(W, H, a.crop.data());
        if (b.width() <= 0 || b.height() <= 0) throw InputError("--crop: the crop window holds no pixel");
        scene.setPixelBounds(b);
    }
    if (!a.pixelBounds.empty()) {
        const std::vector<int>& p = a.pixelBounds;
        if (p[0] < 0 || p[2] < 0 || p[1] > W || p[3] > H || p[0] >= p[1] || p[2] >= p[3])
            throw InputError("--pixelbounds x0 x1 y0 y1 needs 0 <= x0 < x1 <= " + std::to_string(W) +
                             " and 0 <= y0 < y1 <= " + std::to_string(H) + " (the film's resolution)");
        scene.setPixelBounds(PixelBounds{p[0], p[1], p[2], p[3]});
    }
    // pbrt-v4 warns too: a scene without emitters renders black.
    if (scene.lights().empty()) warning("the scene has no light source or emitting shape: the image will be black");
    std::unique_ptr<Integrator>& integrator = setup.integrator;
    if (a.lightPaths > 0 || a.lightPathsAuto) {
        if (settings.integrator != "bdpt")
            throw InputError("--light-paths needs --integrator bdpt (the render uses \"" + settings.integrator + "\")");
        if (a.lightPaths > 0) settings.bdptLightPaths = a.lightPaths;
    }
    if (a.lightSamples > 0) settings.lightSamples = a.lightSamples;
    integrator = createIntegrator(settings.integrator, scene, a.mis);
    // Not silent: their weights jump where densities cross, and rounding there biases a little.
    if (!a.mis.empty()) {
        const MisHeuristic h = parseMisWeighting(a.mis).heuristic;
        if (h == MisHeuristic::Maximum || h == MisHeuristic::Cutoff)
            warning("--mis " + a.mis + ": weights that jump where densities cross can lose up to a few tenths of "
                    "a percent where strategies sample alike (docs/mis.md); power and balance have no such bias");
    }
    // A darker image with no word of why is a wrong answer: each class of paths the integrator
    // cannot sample is named once, with its lights, materials and camera (transport/coverage.h).
    for (const UnsampledPaths& c : unsampledPaths(scene, settings.integrator))
        warning("integrator \"" + settings.integrator + "\" will render part of this scene's light black: " + c.message);
    if (const std::string why = inconsistentSurfaces(scene, settings.integrator); !why.empty())
        warning("integrator \"" + settings.integrator + "\" may render some curves other than path tracing: " + why);
    const AdaptiveMode adaptive = parseAdaptiveMode(a.adaptive);
    if (adaptive != AdaptiveMode::None && integrator->splats())
        throw InputError("--adaptive " + a.adaptive + " needs --integrator path: light tracing, BDPT and Metropolis "
                         "splat paths anywhere on the film, so a pixel's samples do not make its value");
    BDPTIntegrator*& bdpt = setup.bdpt;
    if (a.strategyImages()) {
        bdpt = dynamic_cast<BDPTIntegrator*>(integrator.get());
        if (!bdpt) throw InputError("--bdpt-strategies needs --integrator bdpt (the scene asks for \"" +
                                    settings.integrator + "\")");
        // Below 1 most samples are the path tracer's, which has no strategies (s, t) to record.
        if (bdpt->lightPathShare() < 1)
            throw InputError("--bdpt-strategies needs every sample to be a BDPT sample: drop --light-paths "
                             "(below 1 the other samples are path tracing's)");
        // Every depth the render makes, so that the weighted images sum to it; their memory grows
        // with the square of maxdepth and is checked (use --crop or a smaller --maxdepth if too much).
        bdpt->recordStrategies(settings.maxDepth);
    }
    RenderOptions& opts = setup.opts;
    opts.spp = settings.spp;
    opts.timeLimit = a.time;
    const int cores = std::max(1, tbb::this_task_arena::max_concurrency());
    if (a.threads > cores)
        warning("--threads " + std::to_string(a.threads) + ": this machine has " + std::to_string(cores) +
                " hardware threads; using " + std::to_string(cores));
    opts.threads = a.threads > 0 ? std::min(a.threads, cores) : cores;
    opts.seed = settings.seed;
    opts.sampler = settings.sampler;
    opts.progress = !a.quiet;
    opts.adaptive = adaptive;
    if (a.shadowRoulette > 0) {
        const std::string& n = settings.integrator;
        if (n != "path" && n != "volpath" && n != "light" && n != "bdpt")
            throw InputError("--shadow-roulette applies to path, light and bdpt (the render uses \"" + n +
                             "\"): a Markov chain's target must not be a random estimate");
        if (adaptive != AdaptiveMode::None)
            throw InputError("--shadow-roulette needs uniform sampling: its threshold follows the image between "
                             "passes of equal size (leave out --adaptive)");
        if (scene.hasMedia())
            warning("--shadow-roulette: in a scene with participating media, connections estimate transmittance "
                    "and are all traced");
        opts.shadowRoulette = a.shadowRoulette;
    }
    // --stats: for stratified and QMC samplers K independently scrambled sample sets whose
    // spread gives the variance (transport/scrambled_sets.h; the same image on any number of
    // processes), and each technique's figures (one process: the sums are each process's).
    // Not with adaptive sampling (unequal pixels) or checkpoints (their sample sets are the
    // resume's).
    const bool uniformDriver = settings.integrator == "path" || settings.integrator == "light" || settings.integrator == "bdpt";
    if (a.stats() && uniformDriver && adaptive == AdaptiveMode::None) {
        opts.techniqueFigures = distributed::size() == 1;
        opts.batches = batchCount(opts.spp);
        if (a.checkpoint.empty() && a.resume.empty()) {
            opts.scramblings = scramblingCount(opts.sampler, opts.spp);
        }
    }
    // --light-paths auto: a pilot of path tracing's and BDPT's samples chooses the share.
    if (a.lightPathsAuto && !a.resume.empty())
        throw InputError("--light-paths auto cannot resume: its pilot is timed and may choose another share; give "
                         "the share the first run chose (its summary line, or --stats' light_paths_per_sample)");
    // Strategy images need every sample to be BDPT's: then the share stays 1.
    setup.choosesLightPaths = a.lightPathsAuto && !a.strategyImages();
    // Only what will be shown or written: a quiet render without --stats or --aov variance
    // leaves the film's luminance moments out (bench/README.md, scene loading).
    opts.errorEstimate = !a.quiet || !a.statsFile.empty();
    opts.varianceImage = a.varianceImage();
    opts.pixelSamples = false;
}

void completeResult(const Scene& scene, RenderResult& r) {
    r.distributed.reductionBytes = distributed::traffic().bytes;
    r.distributed.reductionSeconds = distributed::traffic().seconds;
    const PixelBounds& pb = scene.pixelBounds();
    const int filmW = scene.camera().params().xRes, filmH = scene.camera().params().yRes;
    if (pb.width() != filmW || pb.height() != filmH)
        for (Image* img : {&r.image, &r.variance}) {
            img->filmWidth = filmW;
            img->filmHeight = filmH;
            img->x0 = pb.x0;
            img->y0 = pb.y0;
        }
}

NoiseKnown noiseKnown(const RenderResult& r) {
    NoiseKnown k;
    k.noise = r.meanSpp >= 2;
    k.resumed = r.resumedSpp > 0;
    k.efficiency = k.noise && !k.resumed && std::isfinite(r.efficiency);
    return k;
}

namespace {

// The classes of paths the integrator cannot sample (transport/coverage.h), as the warnings said.
nlohmann::json unsampledPathsJson(const Scene& scene) {
    nlohmann::json out = nlohmann::json::array();
    for (const UnsampledPaths& c : unsampledPaths(scene, scene.settings().integrator))
        out.push_back({{"class", c.id}, {"every_integrator", c.everyIntegrator}, {"message", c.message}});
    return out;
}

// Each technique's figures (transport/technique_tally.h), then the whole image's.
nlohmann::json techniquesJson(const RenderResult& r) {
    nlohmann::json list = nlohmann::json::array();
    auto figures = [](nlohmann::json e, const TechniqueTally::Figure& f) {
        e["mean"] = f.mean;
        e["share"] = f.share;
        e["variance"] = f.variance;
        e["relative_variance"] = f.relativeVariance;
        e["efficiency"] = f.efficiency;
        return e;
    };
    for (size_t k = 0; k < r.techniques.size() && k < r.techniqueFigures.size(); ++k) {
        const RenderTechnique& t = r.techniques[k];
        if (!t.possible) continue;
        nlohmann::json e = {{"name", t.name}, {"splat", t.splat}};
        if (t.s >= 0) {
            e["s"] = t.s;
            e["t"] = t.t;
            e["depth"] = t.s + t.t - 2;
        }
        list.push_back(figures(e, r.techniqueFigures[k]));
    }
    return {{"list", list},
            {"image", figures(nlohmann::json::object(), r.techniqueFigures.back())},
            {"batches", r.techniqueBatches}};
}

}  // namespace

nlohmann::json renderStatistics(const Scene& scene, const RenderArgs& a, const RenderSetup& setup,
                                const RenderResult& r, const PathStats& run, const std::string& sceneFile,
                                const std::vector<std::string>& outputs, bool interrupted) {
    const RenderSettings& settings = scene.settings();
    nlohmann::json byPurpose = nlohmann::json::object();
    for (const auto& [purpose, t] : distributed::trafficByPurpose())
        byPurpose[purpose] = {{"bytes", t.bytes}, {"seconds", t.seconds}};
    double secs = std::max(r.seconds, 1e-9);
    const NoiseKnown known = noiseKnown(r);
    uint64_t rays = r.stats.rays + r.stats.shadowRays;
    // Rates are this run's work over this run's time (after --resume, the totals are not).
    const double runRays = double(run.rays + run.shadowRays);
    nlohmann::json stats = {
        {"scene", sceneFile},
        {"outputs", outputs},
        {"integrator", settings.integrator},
        {"color", settings.spectral ? "spectral" : "rgb"},
        {"sampler", settings.sampler},
        {"adaptive", a.adaptive.empty() ? "none" : a.adaptive},
        {"resolution", {scene.camera().params().xRes, scene.camera().params().yRes}},
        {"pixels", scene.pixelBounds().area()},
        {"threads", setup.opts.threads},
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
        {"shadow_rays_skipped", r.stats.shadowRaysSkipped},
        {"rays_per_s", runRays / secs},
        {"mean_pixel_variance", known.noise ? nlohmann::json(r.error.meanVariance) : nlohmann::json()},
        {"mean_relative_variance", known.noise ? nlohmann::json(r.error.meanRelativeVariance) : nlohmann::json()},
        {"efficiency", known.efficiency ? nlohmann::json(r.efficiency) : nlohmann::json()},
        {"nonfinite_guarded", r.stats.guarded},
        {"nonfinite_samples_rejected", r.rejectedSamples},
        {"warnings", warningCount()},
        {"unsampled_paths", unsampledPathsJson(scene)},
        {"memory_limit_bytes", memoryLimit()},
    };
    if (settings.integrator == "bdpt") stats["light_paths_per_sample"] = settings.bdptLightPaths;
    if (settings.bdptLightPathsAuto)
        stats["light_paths_auto"] = {{"path_variance_time", settings.bdptPilotPath},
                                     {"bdpt_variance_time", settings.bdptPilotBdpt}};
    stats["shadow_roulette"] = a.shadowRoulette;
    if (settings.integrator == "path") stats["light_samples"] = settings.lightSamples;
    // How the variances were estimated (docs/strategy-figures.md).
    stats["variance_estimator"] = r.scramblings > 1 ? "scramblings"
                                  : r.metropolis.present || !setup.integrator->splats() ? "sample variance"
                                                                                         : "half images";
    stats["scramblings"] = r.scramblings;
    if (!r.techniqueFigures.empty() && !r.techniques.empty()) stats["techniques"] = techniquesJson(r);
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
    if (std::isfinite(settings.maxComponentValue))
        stats["max_component_value"] = {{"value", settings.maxComponentValue}, {"note", kClampNote}};
    return stats;
}

}  // namespace ps
