// Renders a scene and measures, in the same run, how fast raw Embree traces incoherent
// closest-hit rays through the same BVH: the ratio says how close the renderer is to the
// traversal limit.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "math/warp.h"
#include "mc/rng.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/renderer.h"
#include "util/error.h"

using namespace ps;

static double rawEmbreeRaysPerSecond(const Scene& scene, long long nRays, int threads) {
    // Random incoherent rays, generated before timing: origins uniform in the central half
    // of the scene's bounds, directions uniform on the sphere.
    Vec3 c = scene.boundsCenter();
    float r = scene.boundsRadius() * 0.5f;
    const int chunk = 1 << 16;
    const long long nChunks = std::max(1LL, nRays / chunk);
    std::vector<RTCRayHit> rays(size_t(chunk) * 16);  // a pool reused across chunks
    Rng rng(1);
    for (RTCRayHit& rh : rays) {
        Vec3 o = c + Vec3(rng.uniform() * 2 - 1, rng.uniform() * 2 - 1, rng.uniform() * 2 - 1) * r;
        Vec3 d = sampleUniformSphere({rng.uniform(), rng.uniform()});
        rh.ray.org_x = o.x; rh.ray.org_y = o.y; rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x; rh.ray.dir_y = d.y; rh.ray.dir_z = d.z;
        rh.ray.time = 0; rh.ray.mask = ~0u; rh.ray.id = 0; rh.ray.flags = 0;
    }
    std::vector<unsigned> hits(size_t(nChunks), 0);
    tbb::task_arena arena(threads);
    auto t0 = std::chrono::steady_clock::now();
    arena.execute([&] {
        tbb::parallel_for(0LL, nChunks, [&](long long ci) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            unsigned h = 0;
            size_t base = size_t(ci % 16) * chunk;
            for (int i = 0; i < chunk; ++i) {
                RTCRayHit rh = rays[base + i];
                rh.ray.tnear = 0;
                rh.ray.tfar = 1e30f;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene.embreeScene(), &ctx, &rh);
                h += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
            hits[size_t(ci)] = h;
        });
    });
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return double(nChunks * chunk) / secs;
}

int main(int argc, char** argv) {
    CLI::App app{"Render benchmark: renderer rays/s against raw Embree rays/s on the same scene"};
    std::string scenePath = "../shared/scenes/cornell-box/scene-v4-256.pbrt";
    int spp = 64, maxDepth = 8, threads = 2;
    std::string json;
    app.add_option("scene", scenePath, "Scene file");
    app.add_option("--spp", spp, "Samples per pixel");
    app.add_option("--maxdepth", maxDepth, "Maximum depth");
    app.add_option("--threads", threads, "Threads");
    app.add_option("--json", json, "Write results as JSON");
    CLI11_PARSE(app, argc, argv);
    setWarningsQuiet(true);
    try {
        auto scene = buildScene(parseSceneFile(scenePath));
        scene->settings().maxDepth = maxDepth;
        auto integrator = createIntegrator("path", *scene);
        RenderOptions opts;
        opts.spp = spp;
        opts.threads = threads;
        opts.progress = false;
        RenderResult r = render(*scene, *integrator, opts);
        uint64_t rays = r.stats.rays + r.stats.shadowRays;
        double rendRate = double(rays) / r.seconds;
        double rawRate = rawEmbreeRaysPerSecond(*scene, (long long)rays, threads);
        nlohmann::json out = {{"scene", scenePath}, {"spp", spp}, {"maxdepth", maxDepth}, {"threads", threads},
                              {"render_seconds", r.seconds}, {"camera_paths_per_s", r.stats.cameraPaths / r.seconds},
                              {"rays", rays}, {"rays_per_s", rendRate}, {"raw_embree_rays_per_s", rawRate},
                              {"ray_rate_ratio", rendRate / rawRate}};
        std::printf("render: %.3f s, %.3g camera paths/s, %.3g rays/s (%llu rays)\n", r.seconds,
                    r.stats.cameraPaths / r.seconds, rendRate, (unsigned long long)rays);
        std::printf("raw Embree rtcIntersect1, same BVH, same ray count, random incoherent rays: %.3g rays/s\n", rawRate);
        std::printf("ratio renderer/raw: %.2f\n", rendRate / rawRate);
        if (!json.empty()) std::ofstream(json) << out.dump(2) << "\n";
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
}
