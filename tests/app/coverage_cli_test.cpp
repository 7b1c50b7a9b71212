// What the render command says about light an integrator cannot sample (transport/coverage.h),
// and every integrator at a very large maxdepth: it renders in memory proportional to what it
// uses, or refuses naming its limit (mmlt's bootstrap of bootstrapsamples x (maxdepth + 1)
// paths once ran out of memory at maxdepth 1000).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <filesystem>
#include <fstream>

#include "render/mlt_scenes.h"
#include "run_binary.h"

namespace {

namespace fs = std::filesystem;

struct SceneFile {
    fs::path path;
    explicit SceneFile(const std::string& text, const std::string& name) {
        path = fs::temp_directory_path() / (name + "-" + std::to_string(getpid()) + ".pbrt");
        std::ofstream(path) << text;
    }
    ~SceneFile() { fs::remove(path); }
};

std::string render(const SceneFile& f, const std::string& args) {
    return "render " + f.path.string() + " -o " + (fs::temp_directory_path() / "coverage-cli.pfm").string() + " " + args;
}

TEST(CoverageCli, LightTracingWarnsWhereItCannotSample) {
    std::string mirror = ps::test::box("5 5 5", "0.7 0.2 0.2", "0.2 0.7 0.2");
    mirror.insert(mirror.rfind("Shape \"sphere\""), "Material \"conductor\" \"float roughness\" [ 0 ]\n");
    const SceneFile withMirror(mirror, "mirror"), diffuse(ps::test::box("5 5 5", "0.7 0.2 0.2", "0.2 0.7 0.2"), "diffuse");
    auto r = ps::test::runPathspace(render(withMirror, "--integrator light --spp 1"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("integrator \"light\" will render part of this scene's light black: light tracing cannot "
                         "show what the camera sees in a specular surface"),
              std::string::npos)
        << r.out;
    r = ps::test::runPathspace(render(diffuse, "--integrator light --spp 1"));
    EXPECT_EQ(r.out.find("will render part"), std::string::npos) << r.out;
    r = ps::test::runPathspace(render(withMirror, "--integrator bdpt --spp 1"));
    EXPECT_EQ(r.out.find("will render part"), std::string::npos) << r.out;
}

TEST(CoverageCli, EveryIntegratorAtMaxDepth1000) {
    const SceneFile box(ps::test::withBootstrap(ps::test::box("5 5 5", "0.7 0.2 0.2", "0.2 0.7 0.2"), 1000), "deep");
    for (const char* integrator : {"path", "light", "bdpt", "pssmlt", "mmlt"}) {
        const auto r = ps::test::runPathspace(render(box, std::string("--integrator ") + integrator +
                                                              " --maxdepth 1000 --spp 2 --quiet"));
        EXPECT_EQ(r.status, 0) << integrator << ": " << r.out;
    }
    rusage children{};
    getrusage(RUSAGE_CHILDREN, &children);
    EXPECT_LT(children.ru_maxrss, 1L << 20) << "KB: the largest of them took over 1 GB";
    // Veach's mlt keeps path lengths in a byte and says so.
    const auto r = ps::test::runPathspace(render(box, "--integrator mlt --maxdepth 1000 --spp 1"));
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("supports maxdepth up to 254"), std::string::npos) << r.out;
}

}  // namespace
