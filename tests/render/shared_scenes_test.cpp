// Every shared test scene the supported subset covers loads and renders (a small crop at
// low sample count) without error, producing finite, non-black pixels.
#include <gtest/gtest.h>

#include <filesystem>

#include "render_helpers.h"
#include "shared_data.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

class SharedScene : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedScene, RendersWithoutError) {
    fs::path file = fs::path(PATHSPACE_SHARED_DIR) / "scenes" / GetParam();
    REQUIRE_SHARED_DATA(file);
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneFile(file.string());
    auto scene = buildScene(desc);
    // A 48x48 crop around the image centre keeps this quick.
    int W = scene->camera().params().xRes, H = scene->camera().params().yRes;
    scene->setPixelBounds({W / 2 - 24, W / 2 + 24, H / 2 - 24, H / 2 + 24});
    auto integrator = createIntegrator(scene->settings().integrator, *scene);
    RenderOptions opts;
    opts.spp = 2;
    opts.progress = false;
    RenderResult r = render(*scene, *integrator, opts);
    ASSERT_EQ(r.image.width, 48);
    double sum = 0;
    for (float v : r.image.rgb) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
    }
    EXPECT_GT(sum, 0.0) << "image is black";
    EXPECT_EQ(r.rejectedSamples, 0);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, SharedScene,
    ::testing::Values("cornell-box/scene-v4.pbrt", "cornell-box/scene-v4-256.pbrt", "cornell-box-measured/scene-v4.pbrt",
                      "veach-mis/scene-v4.pbrt", "veach-mis/scene-v4-320x180.pbrt", "veach-mis-classic/scene-v4.pbrt",
                      "veach-bidir/scene-v4.pbrt", "veach-bidir/scene-v4-256.pbrt", "veach-ajar/scene-v4.pbrt",
                      "veach-ajar/scene-v4-checkerfloor.pbrt", "water-caustic/scene-v4.pbrt",
                      "caustic-glass/caustic-glass-v4.pbrt", "caustic-glass/caustic-glass-v4-210x300.pbrt"),
    [](const ::testing::TestParamInfo<const char*>& info) {
        std::string s = info.param;
        for (char& c : s)
            if (!isalnum(static_cast<unsigned char>(c))) c = '_';
        return s;
    });

}  // namespace
