#include "app/verify_command.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "app/command_line.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/output_checks.h"
#include "image/image.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "util/error.h"
#include "verify/verify.h"

namespace ps {

namespace {

std::string fixed(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// One panel per compared integrator, side by side: its mean image in grey, each block tinted
// by how far it is from the reference (green within 2 sigma, yellow within 4, red brighter
// and blue darker beyond), scaled up so that a small film stays legible.
Image disagreementMap(const verify::VerifyReport& report) {
    std::vector<const verify::IntegratorResult*> shown;
    for (const auto& r : report.results)
        if (r.compared) shown.push_back(&r);
    if (shown.empty()) return Image(1, 1);
    const Image& first = shown.front()->runs.meanImage();
    const int w = first.width, h = first.height, s = std::max(1, 256 / std::max(1, std::max(w, h))), gap = 4;
    Image map(int(shown.size()) * (w * s + gap) - gap, h * s);
    for (size_t k = 0; k < shown.size(); ++k) {
        const verify::IntegratorResult& r = *shown[k];
        const Image& img = r.runs.meanImage();
        for (int i = 0; i < r.runs.blockCount(); ++i) {
            const double z = r.verdict.blockZ[size_t(i)], a = std::fabs(z);
            const Spectrum tint = a < 2 ? Spectrum(0.1f, 0.8f, 0.1f)
                                  : a < 4 ? Spectrum(0.9f, 0.8f, 0.1f)
                                  : z > 0 ? Spectrum(1, 0.1f, 0.1f)
                                          : Spectrum(0.1f, 0.2f, 1);
            const verify::BlockPixels b = verify::blockPixels(i, r.runs.blocksX(), r.runs.blocksY(), w, h);
            for (int y = b.y0; y < b.y1; ++y)
                for (int x = b.x0; x < b.x1; ++x) {
                    const Spectrum c = img.get(x, y);
                    const float l = std::max(0.0f, 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b);
                    const float grey = l / (1 + l);
                    const Spectrum p = Spectrum(0.6f * grey) + tint * 0.4f;
                    for (int dy = 0; dy < s; ++dy)
                        for (int dx = 0; dx < s; ++dx) map.set(int(k) * (w * s + gap) + x * s + dx, y * s + dy, p);
                }
        }
    }
    return map;
}

nlohmann::json toJson(const verify::VerifyReport& report, const std::string& scene, int width, int height) {
    nlohmann::json j;
    j["scene"] = scene;
    j["agree"] = report.allAgree();
    j["interrupted"] = report.interrupted;
    for (const verify::IntegratorResult& r : report.results) {
        nlohmann::json e;
        e["integrator"] = r.name;
        if (!r.skipped.empty()) {
            e["skipped"] = r.skipped;
            j["integrators"].push_back(e);
            continue;
        }
        e["runs"] = r.runs.runs();
        e["seconds"] = r.seconds;
        e["spp"] = r.meanSpp;
        e["image_mean"] = r.runs.image().mean;
        e["image_std_err"] = r.runs.image().stdErr;
        e["compared"] = r.compared;
        if (r.compared) {
            const verify::Verdict& v = r.verdict;
            e["reference"] = r.reference;
            e["agrees"] = v.agrees;
            e["why"] = v.why;
            e["ratio"] = v.ratio;
            e["image_z"] = v.imageZ;
            e["channel_z"] = {v.channelZ[0], v.channelZ[1], v.channelZ[2]};
            e["resolution"] = v.resolution;
            e["chi2"] = v.chi2;
            e["chi2_limit"] = v.chi2Limit;
            e["block_z"] = v.blockZ;
            e["blocks"] = {r.runs.blocksX(), r.runs.blocksY()};
            const verify::BlockPixels b = verify::blockPixels(v.worstBlock, r.runs.blocksX(), r.runs.blocksY(), width, height);
            e["worst_block"] = {{"index", v.worstBlock}, {"z", v.blockZ[size_t(v.worstBlock)]},
                                {"pixels", {b.x0, b.y0, b.x1, b.y1}}};
        }
        j["integrators"].push_back(e);
    }
    return j;
}

}  // namespace

void VerifyCommand::attach(CLI::App& app) {
    cmd_ = app.add_subcommand("verify",
                              "Render a scene with every integrator that can sample it and check that they agree "
                              "within their measured noise (exit status 0 when they do, 3 when not)");
    cmd_->add_option("scene", scene_, "pbrt-v4 scene file")->required();
    cmd_->add_option("--time", time_, "seconds for the whole verification, shared by the integrators (default 60)")
        ->check(CLI::PositiveNumber);
    cmd_->add_option("--spp", spp_, "samples (Metropolis: mutations) per pixel of each run, instead of --time")
        ->check(CLI::PositiveNumber);
    cmd_->add_option("--runs", runs_, "independent renders per integrator, whose spread gives the error (default 12)")
        ->check(CLI::Range(3, 1000));
    cmd_->add_option("--blocks", blocks_, "compare N x N blocks of the image (default 4)")->check(CLI::Range(1, 64));
    cmd_->add_option("--integrators", integrators_, "which to run (default: path,light,bdpt,pssmlt,mmlt,mlt)")
        ->delimiter(',');
    cmd_->add_option("--threads", threads_, "threads (default: all cores)")->check(CLI::NonNegativeNumber);
    cmd_->add_option("--seed", seed_, "first run's seed (run k uses seed + k)")->check(CLI::NonNegativeNumber);
    cmd_->add_option("--maxdepth", maxDepth_, "override the scene's maximum path depth")->check(CLI::NonNegativeNumber);
    cmd_->add_option("--two-stage", twoStage_,
                     "Metropolis integrators' two-stage pilot (default 0: the plain target, whose image mean "
                     "varies far less between runs)")
        ->check(CLI::NonNegativeNumber);
    cmd_->add_option("--color", color_, "spectral (default) or rgb")->check(CLI::IsMember({"spectral", "rgb"}));
    cmd_->add_option("--map", map_, "PNG map of the differences (default: SCENE-verify.png here)");
    cmd_->add_option("--json", json_, "JSON report (default: SCENE-verify.json here)");
    cmd_->add_flag("--quiet", quiet_, "print only the result line");
    refuseOptionsAsValues(cmd_);
}

int VerifyCommand::run() {
    const std::string stem = std::filesystem::path(scene_).stem().string();
    if (map_.empty()) map_ = stem + "-verify.png";
    if (json_.empty()) json_ = stem + "-verify.json";
    if (std::filesystem::path(map_).extension() != ".png") throw InputError("--map \"" + map_ + "\": must end in .png");
    checkFileWritable(map_, "--map");
    checkFileWritable(json_, "--json");
    for (const std::string& name : integrators_)
        if (std::find(verify::allIntegrators().begin(), verify::allIntegrators().end(), name) ==
            verify::allIntegrators().end())
            throw InputError("--integrators: unknown integrator \"" + name + "\" (available: path, light, bdpt, pssmlt, "
                             "mmlt, mlt)");

    SceneDescription desc = parseSceneFile(scene_);
    auto scene = buildScene(desc, color_ == "spectral");
    if (maxDepth_ >= 0) scene->settings().maxDepth = maxDepth_;

    verify::VerifyOptions o;
    o.integrators = integrators_;
    o.runs = runs_;
    o.seconds = spp_ > 0 ? 0 : time_;
    o.spp = spp_;
    o.threads = threads_;
    o.seed = uint64_t(seed_);
    o.blocksX = o.blocksY = blocks_;
    const InterruptHandlers interrupts{SIGINT, SIGTERM};
    o.cancel = InterruptHandlers::flag();
    o.configure = [this](const std::string&, RenderSettings& st) { st.mltTwoStage = float(twoStage_); };
    if (!quiet_ && isatty(fileno(stderr)))
        o.onRun = [](const std::string& name, int run, int runs) {
            std::fprintf(stderr, "\r  rendering %-6s run %d/%d ", name.c_str(), run + 1, runs);
            std::fflush(stderr);
        };
    if (!quiet_)
        std::printf("verify %s: %d runs per integrator, %s\n", scene_.c_str(), runs_,
                    spp_ > 0 ? (std::to_string(spp_) + " samples per pixel each").c_str()
                             : (fixed("%.0f", time_) + " s in all").c_str());
    const verify::VerifyReport report = verify::verifyScene(*scene, o);
    if (o.onRun) std::fprintf(stderr, "\r%40s\r", "");

    const int w = scene->pixelBounds().width(), h = scene->pixelBounds().height();
    std::vector<std::string> differ;
    double resolution = 0;
    for (const verify::IntegratorResult& r : report.results) {
        if (!r.skipped.empty()) {
            if (!quiet_) std::printf("  %-6s  not run: %s\n", r.name.c_str(), r.skipped.c_str());
            continue;
        }
        if (!r.compared) {
            if (!quiet_ && !report.interrupted) std::printf("  %-6s  nothing to compare it with\n", r.name.c_str());
            continue;
        }
        const verify::Verdict& v = r.verdict;
        resolution = std::max(resolution, v.resolution);
        if (!v.agrees) differ.push_back(r.name);
        if (quiet_) continue;
        const verify::BlockPixels b = verify::blockPixels(v.worstBlock, r.runs.blocksX(), r.runs.blocksY(), w, h);
        std::printf("  %-6s  %-7s image %.5g +- %.2g, %.4f of the reference (%+.1f sigma); worst block: pixels x %d-%d, "
                    "y %d-%d at %+.1f sigma; blocks' chi-square %.1f (bound %.1f)\n",
                    r.name.c_str(), v.agrees ? "agrees" : "DIFFERS", r.runs.image().mean, r.runs.image().stdErr,
                    v.ratio, v.imageZ, b.x0, b.x1 - 1, b.y0, b.y1 - 1, v.blockZ[size_t(v.worstBlock)], v.chi2,
                    v.chi2Limit);
        if (!v.agrees) std::printf("          %s\n", v.why.c_str());
    }
    const bool agree = report.allAgree();
    if (report.comparedCount() > 0) {
        writeImage(map_, disagreementMap(report));
        std::ofstream(json_) << toJson(report, scene_, w, h).dump(2) << "\n";
    }
    if (report.interrupted) {
        std::printf("interrupted: nothing was compared\n");
        return kExitInterrupted;
    }
    if (report.comparedCount() == 0) {
        std::printf("nothing to compare: fewer than two integrators can render this scene\n");
        return kExitDisagree;
    }
    std::string line = agree ? "all " + std::to_string(report.comparedCount()) + " integrators agree"
                             : std::to_string(differ.size()) + " of " + std::to_string(report.comparedCount()) +
                                   " differ:";
    for (const std::string& d : differ) line += " " + d;
    std::printf("%s (each compared with the others that agree; a uniform bias above %.1f%% would show)\n",
                line.c_str(), 100 * resolution);
    if (!quiet_) std::printf("map: %s, report: %s\n", map_.c_str(), json_.c_str());
    return agree ? kExitOk : kExitDisagree;
}

}  // namespace ps
