// The classes of paths that no technique of an integrator samples (transport/coverage.h,
// thesis §1.1 and §10.2): each detected on a scene that has it, none on scenes that do not,
// and none new on the bundled and shared scenes (what they truly miss is asserted instead).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "render/scene_builder.h"
#include "scene/parser.h"
#include "shared_data.h"
#include "transport/coverage.h"
#include "util/error.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kIntegrators = {"path", "light", "bdpt", "pssmlt", "mmlt", "mlt"};

std::unique_ptr<Scene> load(const std::string& text) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(text, ".", "<test>");
    return buildScene(desc);
}

std::unique_ptr<Scene> loadFile(const fs::path& file) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneFile(file.string());
    return buildScene(desc);
}

// The class ids `integrator` misses, in order.
std::vector<std::string> ids(const Scene& scene, const std::string& integrator) {
    std::vector<std::string> out;
    for (const UnsampledPaths& c : unsampledPaths(scene, integrator)) out.push_back(c.id);
    return out;
}

const UnsampledPaths* find(const std::vector<UnsampledPaths>& classes, const std::string& id) {
    for (const UnsampledPaths& c : classes)
        if (c.id == id) return &c;
    return nullptr;
}
// A pointer into a temporary list would dangle: callers keep the list.
const UnsampledPaths* find(std::vector<UnsampledPaths>&& classes, const std::string& id) = delete;

// A floor, a mirror sphere or a diffuse one, a point light or a small area light, and a
// pinhole or a thin-lens camera.
std::string scene(bool mirror, bool pointLight, float lensRadius) {
    std::string s = "LookAt 0 1 4  0 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 40 ] \"float lensradius\" [ " +
                    std::to_string(lensRadius) + " ] \"float focaldistance\" [ 4 ]\n" +
                    "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\nWorldBegin\n";
    s += pointLight ? "LightSource \"point\" \"rgb I\" [ 5 5 5 ] \"point3 from\" [ 0 3 0 ]\n"
                    : "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [ 5 5 5 ]\nTranslate 0 3 0\n"
                      "Shape \"sphere\" \"float radius\" [ 0.1 ]\nAttributeEnd\n";
    s += "Material \"diffuse\"\nShape \"trianglemesh\" \"point3 P\" [ -5 0 -5  5 0 -5  5 0 5  -5 0 5 ] "
         "\"integer indices\" [ 0 1 2 0 2 3 ]\n";
    s += mirror ? "Material \"conductor\" \"float roughness\" [ 0 ]\n" : "Material \"diffuse\"\n";
    s += "AttributeBegin\nTranslate 0 0.5 0\nShape \"sphere\" \"float radius\" [ 0.5 ]\nAttributeEnd\n";
    return s;
}

}  // namespace

// (a) A point light seen in a mirror by a pinhole: missed by every integrator, which says so
// naming the light's directive, the material's and the camera, with Veach's remedies. Path
// tracing misses the caustic too (b), light tracing what the camera sees in the mirror (c).
TEST(UnsampledPaths, DeltaLightThroughAMirrorToAPinhole) {
    auto s = load(scene(true, true, 0));
    for (const std::string& integrator : kIntegrators) {
        const auto classes = unsampledPaths(*s, integrator);
        const UnsampledPaths* a = find(classes, "delta-specular-eye");
        ASSERT_NE(a, nullptr) << integrator;
        EXPECT_TRUE(a->everyIntegrator);
        for (const char* word : {"LightSource \"point\" at <test>:", "Material \"conductor\" at <test>:",
                                 "pinhole camera", "small area light", "roughness floor", "finite aperture"})
            EXPECT_NE(a->message.find(word), std::string::npos) << integrator << ": " << word << " in " << a->message;
    }
    EXPECT_EQ(ids(*s, "path"), (std::vector<std::string>{"delta-caustic", "delta-specular-eye"}));
    EXPECT_EQ(ids(*s, "light"), (std::vector<std::string>{"light-specular", "delta-specular-eye"}));
    EXPECT_EQ(ids(*s, "bdpt"), (std::vector<std::string>{"delta-specular-eye"}));
    // A class every integrator misses leaves comparisons fair: not a missing path for verify.
    EXPECT_EQ(missingPaths(*s, "bdpt"), "");
    EXPECT_NE(missingPaths(*s, "path").find("their caustics are black"), std::string::npos);
    EXPECT_NE(missingPaths(*s, "light").find("cannot show what the camera sees in a specular surface"),
              std::string::npos);
}

// Through a thin lens BDPT, light tracing, pssmlt and Veach's mlt sample class (a) with t = 0;
// the others still miss it, and now it is a difference between integrators (verify leaves
// them out). Also in fog: the light walks' free flights reach the lens (subpaths_media.cpp,
// mlt's PathSpace::trace).
TEST(UnsampledPaths, AThinLensLetsTZeroSampleIt) {
  for (const bool fog : {false, true}) {
    SCOPED_TRACE(fog ? "in fog" : "in a vacuum");
    const std::string text = scene(true, true, 0.05f);
    auto s = load(fog ? "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.1 0.1 0.1 ] "
                        "\"rgb sigma_s\" [ 0.1 0.1 0.1 ]\nMediumInterface \"fog\" \"fog\"\n" + text
                      : text);
    ASSERT_EQ(s->hasMedia(), fog);
    for (const char* integrator : {"bdpt", "light", "pssmlt", "mlt"}) {
        EXPECT_TRUE(samplesLensHits(*s, integrator)) << integrator;
        const std::vector<UnsampledPaths> classes = unsampledPaths(*s, integrator);
        EXPECT_EQ(find(classes, "delta-specular-eye"), nullptr) << integrator;
        if (!fog || std::string(integrator) != "light") EXPECT_EQ(missingPaths(*s, integrator), "") << integrator;
    }
    for (const char* integrator : {"path", "mmlt"}) {
        EXPECT_FALSE(samplesLensHits(*s, integrator)) << integrator;
        const std::vector<UnsampledPaths> classes = unsampledPaths(*s, integrator);  // outlives `a`
        const UnsampledPaths* a = find(classes, "delta-specular-eye");
        ASSERT_NE(a, nullptr) << integrator;
        EXPECT_FALSE(a->everyIntegrator);
        EXPECT_NE(a->message.find("thin-lens camera (lensradius 0.05)"), std::string::npos) << a->message;
        EXPECT_NE(missingPaths(*s, integrator), "") << integrator;
    }
    // In fog around the camera light tracing keeps its class for the scattering near the lens.
    EXPECT_EQ(ids(*s, "light"), fog ? std::vector<std::string>{"light-camera-medium"} : std::vector<std::string>{});
    // --mlt-direct gives mlt's one-bounce paths (the light in the mirror, L S E) to the path
    // tracer, which cannot sample them.
    s->settings().mltMutations = "direct=4";
    EXPECT_FALSE(samplesLensHits(*s, "mlt"));
    const std::vector<UnsampledPaths> direct = unsampledPaths(*s, "mlt");
    const UnsampledPaths* a = find(direct, "delta-specular-eye");
    ASSERT_NE(a, nullptr);
    EXPECT_NE(a->message.find("--mlt-direct renders the one-bounce ones"), std::string::npos) << a->message;
    s->settings().mltMutations = "";
  }
}

// Nothing is missing without a delta light and a specular surface together (light tracing
// keeps its own class for a mirror seen by a pinhole).
TEST(UnsampledPaths, NoClassWhereNothingIsMissing) {
    for (float lens : {0.0f, 0.05f}) {
        auto diffuseWithPoint = load(scene(false, true, lens));
        auto mirrorWithArea = load(scene(true, false, lens));
        for (const std::string& integrator : kIntegrators) {
            EXPECT_EQ(ids(*diffuseWithPoint, integrator), std::vector<std::string>{}) << integrator;
            const auto expected = integrator == "light" && lens == 0 ? std::vector<std::string>{"light-specular"}
                                                                     : std::vector<std::string>{};
            EXPECT_EQ(ids(*mirrorWithArea, integrator), expected) << integrator << " lens " << lens;
        }
    }
}

// The bundled scene and the shared ones: area lights everywhere but in caustic-glass, so no
// integrator newly misses a class there; light tracing keeps its known class where the camera
// sees glass or a mirror. caustic-glass truly has class (a): its spot light's glint in the
// glass, seen by a pinhole, is black in every integrator (and path tracing misses the caustic
// on the floor, as it always said).
TEST(UnsampledPaths, NoNewClassOnTheBundledAndSharedScenes) {
    const fs::path bundled = fs::path(PATHSPACE_SOURCE_DIR) / "scenes" / "cornell-box.pbrt";
    auto box = loadFile(bundled);
    for (const std::string& integrator : kIntegrators)  // its glass sphere: light tracing's own class
        EXPECT_EQ(ids(*box, integrator), integrator == "light" ? std::vector<std::string>{"light-specular"}
                                                               : std::vector<std::string>{})
            << integrator;
    const fs::path shared = fs::path(PATHSPACE_SHARED_DIR) / "scenes";
    REQUIRE_SHARED_DATA(shared);
    using Ids = std::vector<std::string>;
    struct Expect {
        const char* file;
        Ids light;  // light tracing's own classes (before class (a))
        bool deltaSpecularEye = false;
    };
    const std::vector<Expect> scenes = {
        {"cornell-box/scene-v4.pbrt", {}},
        {"cornell-box-measured/scene-v4.pbrt", {}},
        {"veach-mis/scene-v4.pbrt", {}},
        {"veach-mis-classic/scene-v4.pbrt", {}},
        {"veach-bidir/scene-v4.pbrt", {"light-specular"}},
        {"veach-ajar/scene-v4.pbrt", {"light-specular"}},
        {"water-caustic/scene-v4.pbrt", {"light-specular"}},
        {"caustic-glass/caustic-glass-v4.pbrt", {"light-specular"}, true},
    };
    for (const Expect& e : scenes) {
        auto s = loadFile(shared / e.file);
        for (const std::string& integrator : kIntegrators) {
            Ids expected = integrator == "light" ? e.light : Ids{};
            if (e.deltaSpecularEye && integrator == "path") expected.push_back("delta-caustic");
            if (e.deltaSpecularEye) expected.push_back("delta-specular-eye");
            EXPECT_EQ(ids(*s, integrator), expected) << e.file << " " << integrator;
        }
    }
}
