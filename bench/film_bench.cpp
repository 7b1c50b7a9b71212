// The film's accumulation alone: the exact (128-bit fixed-point) sums against the double sums
// they replaced. Renders each scene with the path tracer (its time per sample), then replays
// the same number of samples, in the renderer's order (passes of growing size, 16x16 tiles,
// the same threads), through the film (Film::addSample) and through a copy of the double
// accumulation. A tight loop of additions overstates what they cost inside a render (there
// they overlap other work): bench/film_cost.sh measures the whole render, before and after.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "film/film.h"
#include "mc/rng.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/renderer.h"
#include "util/error.h"

using namespace ps;

namespace {

// The film's per-pixel accumulation before the fixed-point sums (commit e4e9bca's
// Film::addSample without the splat half-buffers, which a path-tracing film skips too).
class DoubleFilm {
public:
    explicit DoubleFilm(PixelBounds b) : bounds_(b), pixels_(size_t(b.area())) {}
    void addSample(int px, int py, Spectrum L, float weight) {
        if (!L.isFinite()) L = Spectrum();
        Pixel& p = pixels_[size_t(py - bounds_.y0) * size_t(bounds_.width()) + size_t(px - bounds_.x0)];
        p.sum[0] += double(L.r) * weight;
        p.sum[1] += double(L.g) * weight;
        p.sum[2] += double(L.b) * weight;
        p.weight += weight;
        p.samples += 1;
        double y = L.luminance();
        p.sumY += y;
        p.sumY2 += y * y;
    }
    double checksum() const {
        double s = 0;
        for (const Pixel& p : pixels_) s += p.sum[0] + p.sumY2;
        return s;
    }

private:
    struct Pixel {
        double sum[3] = {0, 0, 0};
        double weight = 0;
        long long samples = 0;
        double sumY = 0, sumY2 = 0;
        double halfY[2] = {0, 0}, halfWeight[2] = {0, 0};
    };
    PixelBounds bounds_;
    std::vector<Pixel> pixels_;
};

// Feeds `spp` samples per pixel to `add(px, py, L, weight)` as the renderer does: passes of
// 1, 2, 4, ... 64 samples, each over 16x16 tiles in parallel. Seconds.
template <class Add>
double replay(PixelBounds b, int spp, int threads, Add add) {
    tbb::task_arena arena(threads);
    auto t0 = std::chrono::steady_clock::now();
    arena.execute([&] {
        int s0 = 0, pass = 1;
        while (s0 < spp) {
            const int s1 = std::min(spp, s0 + pass);
            tbb::parallel_for(tbb::blocked_range2d<int>(b.y0, b.y1, 16, b.x0, b.x1, 16), [&](const auto& r) {
                for (int py = r.rows().begin(); py < r.rows().end(); ++py)
                    for (int px = r.cols().begin(); px < r.cols().end(); ++px)
                        for (int si = s0; si < s1; ++si) {
                            // Radiance-like values in [0, 2), cheap and different per sample.
                            const uint64_t h = mix64(uint64_t(py) << 40 ^ uint64_t(px) << 20 ^ uint64_t(si));
                            const float u = float(h >> 40) * 0x1p-23f;
                            add(px, py, Spectrum(u, 0.5f * u, 1.5f * u), 1.0f, si);
                        }
            });
            s0 = s1;
            pass = std::min(pass * 2, 64);
        }
    });
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double renderOnce(const Scene& scene, const Integrator& integrator, const RenderOptions& opts) {
    return render(scene, integrator, opts).seconds;
}

struct Measured {
    double renderNsPerSample, fixedNsPerSample, doubleNsPerSample;
};

Measured measure(const std::string& name, const SceneDescription& desc, int spp, int threads, int repeats) {
    auto scene = buildScene(desc);
    auto integrator = createIntegrator("path", *scene);
    RenderOptions opts;
    opts.spp = spp;
    opts.threads = threads;
    opts.progress = false;
    const PixelBounds b = scene->pixelBounds();
    const double samples = double(b.area()) * spp;
    // The best of `repeats` runs of each (the machine is shared: the minimum is the least disturbed).
    double render = 1e30, fixed = 1e30, dbl = 1e30;
    for (int k = 0; k < repeats; ++k) {
        render = std::min(render, renderOnce(*scene, *integrator, opts));
        Film film(scene->camera().params().xRes, scene->camera().params().yRes, b);
        fixed = std::min(fixed, replay(b, spp, threads, [&](int x, int y, Spectrum L, float w, int si) {
                             film.addSample(x, y, L, w, si);
                         }));
        DoubleFilm old(b);
        dbl = std::min(dbl, replay(b, spp, threads, [&](int x, int y, Spectrum L, float w, int) { old.addSample(x, y, L, w); }));
        if (old.checksum() < 0 || film.meanSamplesPerPixel() != spp) std::printf("(replay check failed)\n");
    }
    Measured m{render / samples * 1e9, fixed / samples * 1e9, dbl / samples * 1e9};
    std::printf("%-8s %4d spp, %dx%d, %d threads: render %.1f ns/sample; film alone: fixed point %.1f, double %.1f "
                "ns/sample\n",
                name.c_str(), spp, b.width(), b.height(), threads, m.renderNsPerSample, m.fixedNsPerSample,
                m.doubleNsPerSample);
    return m;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Film benchmark: the 128-bit fixed-point sums' cost per sample against double sums, film alone"};
    std::string cornell = "../shared/scenes/cornell-box/scene-v4-256.pbrt";
    std::string sky = "bench/scenes/sky-sphere.pbrt";  // camera rays mostly miss: the film's share is largest
    int skySpp = 64, cornellSpp = 16, threads = 2, repeats = 3;
    std::string json;
    app.add_option("--cornell", cornell, "The Cornell box scene file");
    app.add_option("--sky", sky, "The sky scene file");
    app.add_option("--sky-spp", skySpp, "Samples per pixel on the sky scene");
    app.add_option("--cornell-spp", cornellSpp, "Samples per pixel on the Cornell box");
    app.add_option("--threads", threads, "Threads");
    app.add_option("--repeats", repeats, "Runs of each measurement (the fastest is kept)");
    app.add_option("--json", json, "Write results as JSON");
    CLI11_PARSE(app, argc, argv);
    setWarningsQuiet(true);
    try {
        nlohmann::json out;
        for (const auto& [name, desc, spp] :
             {std::tuple{std::string("sky"), parseSceneFile(sky), skySpp},
              std::tuple{std::string("cornell"), parseSceneFile(cornell), cornellSpp}}) {
            Measured m = measure(name, desc, spp, threads, repeats);
            out[name] = {{"spp", spp},
                         {"threads", threads},
                         {"render_ns_per_sample", m.renderNsPerSample},
                         {"film_fixed_ns_per_sample", m.fixedNsPerSample},
                         {"film_double_ns_per_sample", m.doubleNsPerSample}};
        }
        if (!json.empty()) std::ofstream(json) << out.dump(2) << "\n";
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
}
