#include "transport/renderer.h"

#include "mc/estimator.h"
#include "mc/sampler.h"

#include "util/error.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <thread>
#include <unistd.h>

namespace ps {

namespace {

constexpr int kTileSize = 16;

struct Tile {
    int x0, x1, y0, y1;
};

std::vector<Tile> makeTiles(const PixelBounds& b) {
    std::vector<Tile> tiles;
    for (int y = b.y0; y < b.y1; y += kTileSize)
        for (int x = b.x0; x < b.x1; x += kTileSize)
            tiles.push_back({x, std::min(x + kTileSize, b.x1), y, std::min(y + kTileSize, b.y1)});
    return tiles;
}

struct ThreadState {
    std::unique_ptr<Sampler> sampler;
    ScratchBuffer scratch;
    PathStats stats;
};

std::string formatSeconds(double s) {
    char buf[32];
    if (s < 60) std::snprintf(buf, sizeof buf, "%.1fs", s);
    else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
    else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
    return buf;
}

// Reports progress on stderr and enforces the time budget from its own thread.
class Monitor {
public:
    Monitor(bool show, double timeLimit, const std::atomic<bool>* cancel, std::atomic<bool>& stop,
            const std::atomic<long long>& done, long long total)
        : show_(show), timeLimit_(timeLimit), cancel_(cancel), stop_(stop), done_(done), total_(total),
          start_(std::chrono::steady_clock::now()), thread_([this] { run(); }) {}
    ~Monitor() {
        {
            std::lock_guard<std::mutex> lock(m_);
            finished_ = true;
        }
        cv_.notify_all();
        thread_.join();
        if (show_) {
            print(true);
            std::fputc('\n', stderr);
        }
    }
    double elapsed() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    void run() {
        std::unique_lock<std::mutex> lock(m_);
        while (!finished_) {
            cv_.wait_for(lock, std::chrono::milliseconds(100));
            if (finished_) break;
            if ((cancel_ && cancel_->load()) || (timeLimit_ > 0 && elapsed() >= timeLimit_)) stop_ = true;
            // Redraw in place on a terminal; elsewhere (logs, CI) only the final line is printed.
            if (show_ && interactive_ && ++ticks_ % 3 == 0) print(false);
        }
    }
    void print(bool final) {
        double t = elapsed();
        double frac = total_ > 0 ? double(done_.load()) / double(total_) : 1.0;
        int width = 30, filled = int(frac * width + 0.5);
        std::string bar(filled, '=');
        bar.resize(width, ' ');
        std::string eta = frac > 0 && !final ? formatSeconds(t / frac - t) : "0s";
        if (timeLimit_ > 0 && !final) eta = formatSeconds(std::max(0.0, std::min(timeLimit_ - t, t / std::max(frac, 1e-9) - t)));
        std::fprintf(stderr, "\rrendering [%s] %5.1f%%  elapsed %s  eta %s   ", bar.c_str(), 100 * frac,
                     formatSeconds(t).c_str(), eta.c_str());
        std::fflush(stderr);
    }

    bool show_;
    double timeLimit_;
    const std::atomic<bool>* cancel_;
    std::atomic<bool>& stop_;
    const std::atomic<long long>& done_;
    long long total_;
    std::chrono::steady_clock::time_point start_;
    std::mutex m_;
    std::condition_variable cv_;
    bool finished_ = false;
    int ticks_ = 0;
    bool interactive_ = isatty(fileno(stderr)) != 0;
    std::thread thread_;
};

}  // namespace

RenderResult render(const Scene& scene, const Integrator& integrator, const RenderOptions& options) {
    const PixelBounds& bounds = scene.pixelBounds();
    const Filter& filter = scene.filter();
    Film film(scene.camera().params().xRes, scene.camera().params().yRes, bounds,
              integrator.splats() ? &filter : nullptr);
    std::vector<Tile> tiles = makeTiles(bounds);
    const float imagingRatio = scene.settings().imagingRatio;
    const int spp = std::max(1, options.spp);
    const bool hasLens = scene.camera().params().lensRadius > 0;

    const int resolution = std::max(scene.camera().params().xRes, scene.camera().params().yRes);
    std::unique_ptr<Sampler> prototype = createSampler(options.sampler, options.seed, spp, resolution);
    if (!prototype) {
        std::string names;
        for (const std::string& n : samplerNames()) names += (names.empty() ? "" : ", ") + n;
        throw InputError("unknown sampler \"" + options.sampler + "\" (available: " + names + ")");
    }
    tbb::enumerable_thread_specific<ThreadState> states([&] {
        ThreadState s;
        s.sampler = prototype->clone();
        return s;
    });

    std::atomic<bool> stop{false};
    std::atomic<long long> samplesDone{0};
    const long long totalSamples = bounds.area() * spp;
    RenderResult result;
    result.targetSpp = spp;
    {
        Monitor monitor(options.progress, options.timeLimit, options.cancel, stop, samplesDone, totalSamples);
        tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
        // Passes of growing size: an early stop leaves every pixel with a similar count,
        // and each pixel is normalised by its own weights, so the image stays unbiased.
        int s0 = 0, pass = 1;
        while (s0 < spp && !stop) {
            int s1 = std::min(spp, s0 + pass);
            arena.execute([&] {
                tbb::parallel_for(size_t(0), tiles.size(), [&](size_t ti) {
                    if (stop.load(std::memory_order_relaxed)) return;
                    ThreadState& st = states.local();
                    const Tile& t = tiles[ti];
                    for (int py = t.y0; py < t.y1; ++py)
                        for (int px = t.x0; px < t.x1; ++px)
                            for (int si = s0; si < s1; ++si) {
                                st.sampler->startPixelSample(px, py, si);
                                FilterSample fs = filter.sample(st.sampler->getPixel2D());
                                CameraSample cs;
                                cs.pFilm = {px + 0.5f + fs.offset.x, py + 0.5f + fs.offset.y};
                                cs.pLens = hasLens ? st.sampler->get2D() : Vec2(0.5f, 0.5f);
                                Ray ray = scene.camera().generateRay(cs);
                                SampleContext ctx{*st.sampler, st.scratch, st.stats, film, si, px, py, fs.weight};
                                Spectrum L = integrator.Li(ray, ctx);
                                st.scratch.reset();
                                film.addSample(px, py, L * imagingRatio, fs.weight, si);
                            }
                    samplesDone.fetch_add((long long)(t.x1 - t.x0) * (t.y1 - t.y0) * (s1 - s0), std::memory_order_relaxed);
                });
            });
            s0 = s1;
            pass = std::min(pass * 2, 64);
        }
        result.seconds = monitor.elapsed();
    }
    for (const ThreadState& st : states) result.stats += st.stats;
    result.meanSpp = film.meanSamplesPerPixel();
    // Every camera sample traced one light path; the imaging ratio scales splats as well.
    const double lightPaths = imagingRatio > 0 ? result.meanSpp * double(bounds.area()) / imagingRatio : 0.0;
    result.lightPaths = lightPaths;
    result.image = film.image(lightPaths);
    result.stoppedEarly = result.meanSpp < spp;
    result.rejectedSamples = film.rejectedSamples();
    result.error = film.errorEstimate(lightPaths);
    result.efficiency = efficiency(result.error.meanRelativeVariance, result.seconds);
    return result;
}

}  // namespace ps
