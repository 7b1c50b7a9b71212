// Same scene and seed give bit-identical images at 1, 2 and 4 threads for every integrator:
// every pixel sample owns its random stream, and the splats of light tracing and BDPT add up
// in fixed point (whatever the order), in per-thread copies or in the shared array.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

std::string sceneText(int xRes, int yRes) {
    return R"(
    LookAt 0 1 3.9  0 1 0  0 1 0
    Camera "perspective" "float fov" [ 40 ]
    Film "rgb" "integer xresolution" [ )" +
           std::to_string(xRes) + R"( ] "integer yresolution" [ )" + std::to_string(yRes) + R"( ]
    Integrator "path" "integer maxdepth" [ 6 ]
    WorldBegin
    LightSource "infinite" "rgb L" [ 0.2 0.2 0.3 ]
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
      Shape "bilinearmesh" "point3 P" [ -0.3 1.9 -0.3  0.3 1.9 -0.3  -0.3 1.9 0.3  0.3 1.9 0.3 ]
    AttributeEnd
    Material "diffuse" "rgb reflectance" [ 0.7 0.6 0.5 ]
    Shape "bilinearmesh" "point3 P" [ -1 0 1  1 0 1  -1 0 -1  1 0 -1 ]
    Material "dielectric" "float eta" [ 1.5 ] "float roughness" [ 0.05 ]
    Translate 0 0.5 0
    Shape "sphere" "float radius" [ 0.5 ]
)";
}

// One image of the scene; the same (integrator, sampler, seed) must reproduce it at any
// thread count.
std::vector<float> renderImage(const std::string& text, const char* integrator, const char* sampler, int threads,
                               uint64_t seed, int spp = 8) {
    SceneDescription desc = parseSceneString(text);
    auto scene = buildScene(desc);
    auto integ = createIntegrator(integrator, *scene);
    RenderOptions o;
    o.spp = spp;
    o.seed = seed;
    o.threads = threads;
    o.sampler = sampler;
    o.progress = false;
    return render(*scene, *integ, o).image.rgb;
}

// How many threads an arena of n slots really runs: n tasks that each wait (up to 30 s) for
// all n to have started. The scheduler keeps to the machine's cores unless allowed more.
int threadsRunning(int n) {
    std::atomic<int> started{0};
    std::set<std::thread::id> ids;
    std::mutex m;
    tbb::task_arena(n).execute([&] {
        tbb::parallel_for(0, n, [&](int) {
            {
                std::lock_guard<std::mutex> lock(m);
                ids.insert(std::this_thread::get_id());
            }
            ++started;
            auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
            while (started.load() < n && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
        }, tbb::simple_partitioner());
    });
    return int(ids.size());
}

void expectSameAtOneTwoFourThreads(const std::string& text, const char* integrator, const char* sampler, int spp = 8) {
    const tbb::global_control allowFour(tbb::global_control::max_allowed_parallelism, 4);  // also on 2 cores
    ASSERT_EQ(threadsRunning(4), 4);
    auto a = renderImage(text, integrator, sampler, 1, 3, spp), b = renderImage(text, integrator, sampler, 2, 3, spp),
         c = renderImage(text, integrator, sampler, 4, 3, spp), d = renderImage(text, integrator, sampler, 2, 4, spp);
    EXPECT_EQ(a, b) << integrator << " " << sampler << ": 1 and 2 threads";
    EXPECT_EQ(a, c) << integrator << " " << sampler << ": 1 and 4 threads";
    EXPECT_NE(a, d) << integrator << " " << sampler << ": the seed must change the image";
}

}  // namespace

TEST(Determinism, PathTracerAtOneTwoFourThreads) {
    for (const std::string& sampler : samplerNames()) expectSameAtOneTwoFourThreads(sceneText(40, 30), "path", sampler.c_str());
}

// Light tracing and BDPT splat onto the film from every thread, each thread into its own
// copy of the splat sums, merged at the end.
TEST(Determinism, SplattingIntegratorsAtOneTwoFourThreads) {
    for (const char* integrator : {"light", "bdpt"}) expectSameAtOneTwoFourThreads(sceneText(40, 30), integrator, "sobol");
}

// When per-thread copies for all the machine's threads would not fit (Film: 1 GiB), every
// thread splats into one shared array of atomics. A machine with 2048 threads is simulated
// by rendering inside an arena of 2048 slots, which makes a 128x96 film take the shared array
// (a copy per slot would need 1.2 GB); its images must equal the per-thread ones bit for bit.
TEST(Determinism, SharedSplatBufferAtOneTwoFourThreads) {
    const std::string text = sceneText(128, 96);
    const double pixels = 128 * 96;
    const int slots = 2048;
    // The film's own rule: the splat memory for `slots` threads is that of a single copy.
    ASSERT_EQ(Film::estimateBytes(pixels, true, slots), Film::estimateBytes(pixels, true, 1));
    ASSERT_GT(Film::estimateBytes(pixels, true, 2), Film::estimateBytes(pixels, true, 1));
    const tbb::global_control allowFour(tbb::global_control::max_allowed_parallelism, 4);
    tbb::task_arena manySlots(slots, slots);  // all slots for masters: asks for no workers
    for (const char* integrator : {"light", "bdpt"}) {
        const std::vector<float> perThread = renderImage(text, integrator, "sobol", 4, 3, 2);
        manySlots.execute([&] {
            for (int threads : {1, 2, 4})
                EXPECT_EQ(renderImage(text, integrator, "sobol", threads, 3, 2), perThread)
                    << integrator << ": shared array at " << threads << " thread(s), per-thread copies at 4";
        });
    }
}
