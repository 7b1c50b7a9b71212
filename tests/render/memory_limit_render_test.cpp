// The memory limit on the render's own buffers: the film (named by its Film directive) and
// BDPT's per-strategy images fail before they are allocated, saying what they need.
#include <gtest/gtest.h>

#include <string>

#include "render_helpers.h"
#include "transport/bdpt.h"
#include "util/memory_limit.h"

using namespace ps;
using namespace ps::test;

namespace {

std::string sceneWithFilm(int xRes, int yRes) {
    return "LookAt 0 0 5  0 0 0  0 1 0\n"
           "Camera \"perspective\" \"float fov\" [ 30 ]\n"
           "Film \"rgb\" \"integer xresolution\" [ " + std::to_string(xRes) + " ] \"integer yresolution\" [ " +
           std::to_string(yRes) + " ]\n"
           "Sampler \"independent\" \"integer pixelsamples\" [ 1 ]\n"
           "WorldBegin\n"
           "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
           "Material \"diffuse\"\n"
           "Shape \"sphere\" \"float radius\" [ 1 ]\n";
}

// The render's InputError message, or "" if it rendered.
std::string renderError(const std::string& scene, const std::string& integrator = "path") {
    try {
        renderString(scene, 1, 7, 1, integrator);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(MemoryLimit, HugeFilmFailsNamingTheFilmDirective) {
    const std::string m = renderError(sceneWithFilm(1000000, 1000000));
    EXPECT_EQ(m.rfind("<test>:3:1: error: Film 1000000x1000000 needs ", 0), 0u) << m;
    EXPECT_NE(m.find(" TiB of memory, more than the limit of "), std::string::npos) << m;
    EXPECT_NE(m.find("(raise it with --max-memory)"), std::string::npos) << m;
    // Beyond the arithmetic guard: out of range whatever the limit.
    const std::string side = renderError(sceneWithFilm(2000000, 1));
    EXPECT_NE(side.find("<test>:3:1: error: Film: resolution 2000000x1 is out of range"), std::string::npos) << side;
}

TEST(MemoryLimit, SmallLimitRejectsAFilmTheDefaultAccepts) {
    const std::string scene = sceneWithFilm(256, 256);
    EXPECT_EQ(renderError(scene), "");
    {
        ScopedMemoryLimit limit(1 << 20);
        const std::string m = renderError(scene);
        EXPECT_NE(m.find("Film 256x256 needs " + formatBytes(uint64_t(Film::estimateBytes(256 * 256, false, 1))) +
                         " of memory, more than the limit of 1.0 MiB"),
                  std::string::npos)
            << m;
        // Splatting integrators also keep splat sums per thread (one thread here).
        const std::string light = renderError(scene, "light");
        EXPECT_NE(light.find("Film 256x256 with splat buffers for 1 thread(s) needs " +
                             formatBytes(uint64_t(Film::estimateBytes(256 * 256, true, 1)))),
                  std::string::npos)
            << light;
    }
    EXPECT_EQ(renderError(scene), "");
}

// The check compares the film's own estimate with the limit: at the estimate it renders.
TEST(MemoryLimit, FilmFitsALimitOfExactlyItsEstimate) {
    const std::string scene = sceneWithFilm(64, 48);
    const uint64_t need = uint64_t(Film::estimateBytes(64 * 48, false, 1));
    ScopedMemoryLimit limit(need);
    EXPECT_EQ(renderError(scene), "");
    setMemoryLimit(need - 1);
    EXPECT_NE(renderError(scene), "");
}

TEST(MemoryLimit, BdptStrategyImagesAreChecked) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(sceneWithFilm(64, 64), ".", "<test>");
    auto scene = buildScene(desc);
    BDPTIntegrator bdpt(*scene, 5);
    ScopedMemoryLimit limit(1 << 20);
    try {
        bdpt.recordStrategies(5);
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind("--bdpt-strategies (52 strategy images of 64x64) needs ", 0), 0u) << m;
        EXPECT_NE(m.find("more than the limit of 1.0 MiB"), std::string::npos) << m;
    }
    setMemoryLimit(limit.saved());
    EXPECT_NO_THROW(bdpt.recordStrategies(5));
}
