#include "app/render_command.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <span>

#include "app/command_line.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_checks.h"
#include "app/render_options.h"
#include "image/image.h"
#include "mc/mis.h"
#include "render/distributed.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/bdpt.h"
#include "transport/checkpoint.h"
#include "transport/integrator.h"
#include "transport/light_path_choice.h"
#include "transport/renderer.h"
#include "util/error.h"
#include "util/input_files.h"
#include "util/memory_limit.h"

namespace ps {

namespace {

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
    if (s.integrator == "bdpt" && (s.bdptLightPaths != 1 || s.bdptLightPathsAuto)) {
        char share[64];
        std::snprintf(share, sizeof share, " | light paths %g%s", s.bdptLightPaths, s.bdptLightPathsAuto ? " (auto)" : "");
        line += share;
    }
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
    RenderSetup setup;
    nlohmann::json checkpointSettings;  // what must match to resume
};

void RenderCommand::attach(CLI::App& app) {
    cmd_ = app.add_subcommand("render", "Render a pbrt-v4 scene file");
    cmd_->add_option("scene", scene_, "pbrt-v4 scene file")->required()->check(CLI::ExistingFile);
    addRenderOptions(cmd_, args_);
    refuseOptionsAsValues(cmd_);
}

void RenderCommand::load(Job& job) {
    const HeldWarnings inFileOrder;  // released when the scene is ready, or on an error
    if (!args_.maxMemory.empty()) setMemoryLimit(*parseByteSize(args_.maxMemory));  // validated by the option
    SceneDescription desc = parseSceneFile(scene_);
    std::unique_ptr<Scene>& scene = job.scene;
    scene = buildScene(desc, args_.color == "spectral");
    configureRender(*scene, args_, job.setup);
    const RenderSettings& settings = scene->settings();
    job.outputs = args_.outputs;
    if (job.outputs.empty()) job.outputs.push_back(std::filesystem::path(settings.outputFile).filename().string());
    job.writeVariance = args_.varianceImage();
    const AdaptiveMode adaptive = job.setup.opts.adaptive;
    const BDPTIntegrator* bdpt = job.setup.bdpt;

    // Checkpoints: what must match to resume (the scene file's bytes and the options that shape
    // the image; not threads, processes or time), then the checkpoint resumed from, checked
    // before anything is rendered or written.
    if (args_.checkpointEvery >= 0 && args_.checkpoint.empty()) throw InputError("--checkpoint-every needs --checkpoint FILE");
    if ((!args_.checkpoint.empty() || !args_.resume.empty()) && (adaptive != AdaptiveMode::None || bdpt))
        throw InputError(std::string(adaptive != AdaptiveMode::None ? "adaptive sampling (--adaptive)" : "--bdpt-strategies") +
                         " does not yet write or resume checkpoints: path, light and bdpt with uniform sampling and "
                         "the Metropolis integrators (pssmlt, mmlt, mlt) do");
    const PixelBounds& bounds = scene->pixelBounds();
    const bool checkpointing = !args_.checkpoint.empty() || !args_.resume.empty();
    nlohmann::json& checkpointSettings = job.checkpointSettings;
    checkpointSettings = {
        {"scene_file_hash", checkpointing ? fileHash(scene_) : ""},
        {"input_files", checkpointing ? inputFileHashes(scene_) : nlohmann::json::object()},
        {"integrator", settings.integrator},
        {"spp", settings.spp},
        {"seed", settings.seed},
        {"sampler", settings.sampler},
        {"maxdepth", settings.maxDepth},
        {"mis", misWeightingName(args_.mis.empty() ? MisWeighting{} : parseMisWeighting(args_.mis))},
        {"resolution", {scene->camera().params().xRes, scene->camera().params().yRes}},
        {"pixels", {bounds.x0, bounds.x1, bounds.y0, bounds.y1}}};
    if (settings.spectral) checkpointSettings["color"] = "spectral";  // absent: RGB, as before the option existed
    // Absent: one light subpath per sample, as before the option existed.
    if (settings.integrator == "bdpt" && settings.bdptLightPaths != 1) checkpointSettings["light_paths"] = settings.bdptLightPaths;
    if (args_.shadowRoulette > 0) checkpointSettings["shadow_roulette"] = args_.shadowRoulette;
    if (settings.lightSamples != 1) checkpointSettings["light_samples"] = settings.lightSamples;  // absent: 1
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
    checkRenderable(*scene, *job.setup.integrator, job.setup.opts);
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
    if (!args_.statsFile.empty()) {
        checkFileWritable(args_.statsFile, "--stats");
        writes.push_back({args_.statsFile, "--stats " + args_.statsFile});
    }
    if (!args_.checkpoint.empty()) {
        checkFileWritable(args_.checkpoint, "--checkpoint");
        writes.push_back({args_.checkpoint, "--checkpoint " + args_.checkpoint});
    }
    if (job.setup.bdpt) {
        std::error_code ec;
        std::filesystem::create_directories(args_.strategiesDir, ec);
        if (ec) throw InputError("--bdpt-strategies: cannot create \"" + args_.strategiesDir + "\": " + ec.message());
        checkWritable((std::filesystem::path(args_.strategiesDir) / "s0_t2.exr").string());
    }
    if (!args_.resume.empty()) resumed = readCheckpoint(args_.resume, job.checkpointSettings);
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
        if (!args_.resume.empty() && same(writes[i].first, args_.resume) && writes[i].second.rfind("--checkpoint", 0) != 0)
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
    Integrator* integrator = job.setup.integrator.get();
    BDPTIntegrator* bdpt = job.setup.bdpt;
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
    if (!args_.resume.empty()) {
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
        job.setup.opts.sampleSets = resumed.sampleSets;
        if (job.setup.opts.spp > resumed.spp) job.setup.opts.sampleSets.push_back(resumed.spp);
        if (!job.setup.opts.sampleSets.empty()) job.checkpointSettings["sample_sets"] = job.setup.opts.sampleSets;
    }

    const InterruptHandlers interrupts{SIGINT, SIGTERM};
    RenderOptions& opts = job.setup.opts;
    opts.cancel = InterruptHandlers::flag();
    if (!args_.resume.empty()) opts.resume = &resumed;
    if (!args_.checkpoint.empty()) {
        opts.checkpointEvery = args_.checkpointEvery >= 0 ? args_.checkpointEvery : 60;
        opts.checkpoint = [&](const CheckpointState& s) { writeCheckpoint(args_.checkpoint, checkpointSettings, s); };
    }
    // --light-paths auto: the pilot chooses the share (transport/light_path_choice.h), within
    // --time.
    std::optional<LightPathChoice> pilot;
    if (job.setup.choosesLightPaths) {
        pilot = chooseLightPathShare(*scene, dynamic_cast<BDPTIntegrator&>(*integrator), opts);
        settings.bdptLightPaths = pilot->share;
        settings.bdptLightPathsAuto = true;
        settings.bdptPilotPath = pilot->pathVarianceTime;
        settings.bdptPilotBdpt = pilot->bdptVarianceTime;
        if (pilot->share != 1) job.checkpointSettings["light_paths"] = pilot->share;
        if (opts.timeLimit > 0) opts.timeLimit = std::max(opts.timeLimit - pilot->seconds, 1e-3);
    }
    RenderResult r = render(*scene, *integrator, opts);
    // A signal to any process interrupted them all (each stops at the same pass boundary).
    bool interrupted = false;
    {
        distributed::Purpose purpose("stop decisions");
        interrupted = distributed::anyOf(InterruptHandlers::interrupted());
    }
    if (bdpt) bdpt->strategyImages()->sumToRoot();
    gatherWarnings();
    if (!root) return interrupted ? kExitInterrupted : kExitOk;
    completeResult(*scene, r);
    for (const std::string& o : outputs) {
        writeImage(o, r.image);
        if (writeVariance) writeImage(variancePath(o), r.variance);
    }
    if (bdpt)
        for (const auto& [name, image] : bdpt->strategyImages()->images(r.lightPaths))
            writeImage((std::filesystem::path(args_.strategiesDir) / (name + ".exr")).string(), image);

    // Rates are this run's work over this run's time (after --resume, the totals are not).
    const PathStats run = args_.resume.empty() ? r.stats : r.stats.since(resumed.stats);
    const nlohmann::json stats =
        renderStatistics(*scene, args_, job.setup, r, run, scene_, outputs, interrupted);
    const NoiseKnown known = noiseKnown(r);
    const bool resumedRun = known.resumed;
    const double secs = std::max(r.seconds, 1e-9);
    const uint64_t rays = r.stats.rays + r.stats.shadowRays;
    const double runRays = double(run.rays + run.shadowRays);
    const MetropolisStats& ms = r.metropolis;
    const bool primarySample = settings.integrator != "mlt";
    const bool clamped = std::isfinite(settings.maxComponentValue);
    if (args_.statsPrint) std::printf("%s\n", stats.dump(2).c_str());
    if (!args_.statsFile.empty()) {
        std::ofstream f(args_.statsFile);
        if (!f) throw InputError("--stats: cannot write \"" + args_.statsFile + "\"");
        f << stats.dump(2) << "\n";
    }
    if (!args_.quiet) {
        std::printf("%s\n", summaryLine(settings, job.setup.opts.threads).c_str());
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
        if (known.efficiency)
            std::printf("noise estimate: mean relative variance %.3g, efficiency 1/(V T) %.3g\n",
                        r.error.meanRelativeVariance, r.efficiency);
        else if (known.noise)
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
        if (!args_.resume.empty()) {
            std::printf("resumed from %s", args_.resume.c_str());
            if (r.resumedSpp > 0) std::printf(" at %d spp", r.resumedSpp);
            if (resumed.spp < opts.spp) std::printf("; --spp raised from its %d to %d", resumed.spp, opts.spp);
            std::printf("\n");
        }
        if (r.checkpoints > 0)
            std::printf("checkpoint %s (%d written) holds %s; --resume %s continues it, to a higher --spp too\n",
                        args_.checkpoint.c_str(), r.checkpoints, r.checkpointKept.c_str(), args_.checkpoint.c_str());
        else if (!args_.checkpoint.empty())
            std::printf("no checkpoint written to %s: the render stopped before it had anything to keep\n",
                        args_.checkpoint.c_str());
        if (r.stoppedEarly) std::printf("stopped early: %s\n", interrupted ? "interrupted" : "time budget reached");
    }
    return interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace ps