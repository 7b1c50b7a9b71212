// What the render command says about light an integrator cannot sample (transport/coverage.h),
// and every integrator at a very large maxdepth: it renders in memory proportional to what it
// uses, or refuses naming its limit (mmlt's bootstrap of bootstrapsamples x (maxdepth + 1)
// paths once ran out of memory at maxdepth 1000).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

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

// A point light seen in a mirror sphere: through a pinhole no integrator samples its highlight
// (thesis §1.1), and the render says so once, naming the light's directive, the material's
// and the camera, with Veach's remedies; --stats records the class. Through a thin lens BDPT's
// t = 0 strategy samples it: no warning there, while path tracing still warns.
TEST(CoverageCli, NamesPathsNoTechniqueSamples) {
    const auto scene = [](const char* lens) {
        return std::string("LookAt 0 1 4  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ] "
                           "\"float lensradius\" [ ") + lens + " ] \"float focaldistance\" [ 4 ]\n" +
               "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\nWorldBegin\n"
               "LightSource \"point\" \"rgb I\" [ 5 5 5 ] \"point3 from\" [ 0 3 0 ]\n"
               "Material \"diffuse\"\nShape \"trianglemesh\" \"point3 P\" [ -5 0 -5  5 0 -5  5 0 5  -5 0 5 ] "
               "\"integer indices\" [ 0 1 2 0 2 3 ]\n"
               "MakeNamedMaterial \"chrome\" \"string type\" \"conductor\" \"float roughness\" [ 0 ]\n"
               "NamedMaterial \"chrome\"\nAttributeBegin\nTranslate 0 0.5 0\nShape \"sphere\" \"float radius\" [ 0.5 ]\n"
               "AttributeEnd\n";
    };
    const SceneFile pinhole(scene("0"), "unsampled-pinhole"), thinLens(scene("0.05"), "unsampled-lens");
    const std::string stats = (fs::temp_directory_path() / ("unsampled-" + std::to_string(getpid()) + ".json")).string();
    auto r = ps::test::runPathspace(render(pinhole, "--integrator bdpt --spp 1 --stats " + stats));
    EXPECT_EQ(r.status, 0) << r.out;
    const std::string warning = "integrator \"bdpt\" will render part of this scene's light black: no technique of "
                                "\"bdpt\" samples the light of LightSource \"point\" at " + pinhole.path.string() + ":5:1 seen "
                                "through MakeNamedMaterial \"chrome\" (conductor) at " + pinhole.path.string() + ":8:1 by the "
                                "pinhole camera (perspective, lensradius 0) (L S+ E paths, thesis sec. 1.1): every integrator "
                                "renders them black. Veach's remedies: a small area light instead of the delta light, a "
                                "roughness floor on the specular materials";
    EXPECT_NE(r.out.find(warning), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("will render part"), r.out.rfind("will render part")) << "one warning per class: " << r.out;
    const auto j = nlohmann::json::parse(std::ifstream(stats));
    ASSERT_EQ(j["unsampled_paths"].size(), 1u) << j.dump();
    EXPECT_EQ(j["unsampled_paths"][0]["class"], "delta-specular-eye");
    EXPECT_EQ(j["unsampled_paths"][0]["every_integrator"], true);
    fs::remove(stats);
    r = ps::test::runPathspace(render(thinLens, "--integrator bdpt --spp 1"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out.find("will render part"), std::string::npos) << r.out;
    r = ps::test::runPathspace(render(thinLens, "--integrator path --spp 1"));
    EXPECT_NE(r.out.find("no technique of \"path\" samples the light of LightSource \"point\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("bdpt, light, pssmlt and mlt sample them through this lens (t = 0)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("the thin-lens camera (lensradius 0.05)"), std::string::npos) << r.out;
}

// Flat and cylinder curves of a material other than hair: every integrator but the path tracer
// warns (light paths meet the strip other than camera rays do); hair curves, ribbons and the
// path tracer do not.
TEST(CoverageCli, LightSideIntegratorsWarnOnRayFacingCurvesOfOtherMaterials) {
    auto withCurve = [](const std::string& type, const std::string& material) {
        std::string scene = ps::test::box("5 5 5", "0.7 0.2 0.2", "0.2 0.7 0.2");
        scene.insert(scene.rfind("Shape \"sphere\""),
                     "AttributeBegin\nMaterial \"" + material + "\"\nShape \"curve\" \"string type\" [ \"" + type +
                         "\" ] \"float width\" [ 0.1 ] \"point3 P\" [ -1 0 0  -0.3 0.5 0  0.3 0 0  1 0.5 0 ]" +
                         (type == "ribbon" ? " \"normal N\" [ 0 0 1  0 0 1 ]" : "") + "\nAttributeEnd\n");
        return scene;
    };
    const std::string phrase = "may render some curves other than path tracing";
    for (const std::string type : {"flat", "cylinder"}) {
        const SceneFile diffuse(withCurve(type, "diffuse"), "curve-diffuse"), hair(withCurve(type, "hair"), "curve-hair");
        for (const std::string integrator : {"light", "bdpt", "mmlt"}) {
            const std::string args = "--integrator " + integrator + " --spp 1" + (integrator == "mmlt" ? " --bootstrap 1000" : "");
            auto r = ps::test::runPathspace(render(diffuse, args));
            EXPECT_EQ(r.status, 0) << r.out;
            EXPECT_NE(r.out.find(phrase), std::string::npos) << type << " " << integrator << ": " << r.out;
            r = ps::test::runPathspace(render(hair, args));
            EXPECT_EQ(r.out.find(phrase), std::string::npos) << type << " " << integrator << ": " << r.out;
        }
        const auto r = ps::test::runPathspace(render(diffuse, "--integrator path --spp 1"));
        EXPECT_EQ(r.out.find(phrase), std::string::npos) << r.out;
    }
    const SceneFile ribbon(withCurve("ribbon", "diffuse"), "curve-ribbon");
    const auto r = ps::test::runPathspace(render(ribbon, "--integrator bdpt --spp 1"));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out.find(phrase), std::string::npos) << r.out;
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
