#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "scene/parser.h"
#include "scene/spectra.h"
#include "scene/tokenizer.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

std::string errorOf(const std::string& text) {
    setWarningsQuiet(true);
    try {
        parseSceneString(text, ".", "s.pbrt");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

void expectNear(Vec3 a, Vec3 b) {
    EXPECT_NEAR(a.x, b.x, 1e-5f);
    EXPECT_NEAR(a.y, b.y, 1e-5f);
    EXPECT_NEAR(a.z, b.z, 1e-5f);
}

}  // namespace

TEST(Tokenizer, TokensCarryLineAndColumn) {
    auto t = Tokenizer::fromString("Shape \"sphere\" # comment\n  [ 1.5 \"a\\\"b\" ]", "f");
    std::vector<Token> toks;
    while (auto x = t->next()) toks.push_back(*x);
    ASSERT_EQ(toks.size(), 6u);
    EXPECT_EQ(toks[0].text, "Shape");
    EXPECT_EQ(toks[1].column, 7);
    EXPECT_EQ(toks[2].text, "[");
    EXPECT_EQ(toks[2].line, 2);
    EXPECT_EQ(toks[2].column, 3);
    EXPECT_EQ(t->dequote(toks[4]), "a\"b");
}

TEST(Parser, ErrorsNameFileLineColumnAndToken) {
    EXPECT_NE(errorOf("WorldBegin\nShape \"sphere\" \"float radius [ 1 ]\n").find("s.pbrt:2:16"), std::string::npos);
    std::string e = errorOf("WorldBegin\n  Frobnicate 3\n");
    EXPECT_NE(e.find("s.pbrt:2:3"), std::string::npos) << e;
    EXPECT_NE(e.find("Frobnicate"), std::string::npos) << e;
    EXPECT_NE(errorOf("WorldBegin\nWorldEnd\n").find("pbrt-v3"), std::string::npos);
    EXPECT_NE(errorOf("Film \"rgb\" \"bool x\" \"true\"").find("s.pbrt:1:21"), std::string::npos);
    EXPECT_NE(errorOf("Film \"rgb\" \"integer xresolution\" [ 2.5 ]").find("integer"), std::string::npos);
    EXPECT_NE(errorOf("Translate [ 1 2 3 ]").find("brackets"), std::string::npos);
    EXPECT_NE(errorOf("WorldBegin\nCamera \"perspective\"").find("before WorldBegin"), std::string::npos);
    EXPECT_NE(errorOf("Shape \"sphere\"").find("after WorldBegin"), std::string::npos);
    EXPECT_NE(errorOf("WorldBegin\nInclude \"does-not-exist.pbrt\"").find("does-not-exist.pbrt"), std::string::npos);
    EXPECT_NE(errorOf("WorldBegin\nMaterial \"matte\"").find("pbrt-v3"), std::string::npos);
    EXPECT_NE(errorOf("Film \"rgb\" \"color x\" [1 1 1]").find("pbrt-v3"), std::string::npos);
    EXPECT_NE(errorOf("Translate 1 nan 3").find("s.pbrt:1:13"), std::string::npos);
    EXPECT_NE(errorOf("Scale 0 1 1").find("singular"), std::string::npos);
    EXPECT_NE(errorOf("WorldBegin\nAttributeEnd").find("unmatched"), std::string::npos);
    EXPECT_NE(errorOf("LookAt 0 0 0 0 0 0 0 1 0").find("LookAt"), std::string::npos);
}

TEST(Parser, DefaultsAndOptions) {
    setWarningsQuiet(true);
    SceneDescription d = parseSceneString("WorldBegin\nShape \"sphere\"");
    EXPECT_EQ(d.camera.type, "perspective");
    EXPECT_EQ(d.integrator.type, "volpath");
    EXPECT_EQ(d.sampler.type, "zsobol");
    EXPECT_EQ(d.filter.type, "gaussian");
    ASSERT_EQ(d.shapes.size(), 1u);
    EXPECT_EQ(d.shapes[0].material.index, 0);
    EXPECT_EQ(d.materials[0].type, "diffuse");
}

// Transform takes 16 numbers column by column; LookAt's CTM is camera-from-world.
TEST(Parser, TransformsFollowPbrt) {
    setWarningsQuiet(true);
    SceneDescription d = parseSceneString(
        "Transform [ 1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1 ]\nCamera \"perspective\"\nWorldBegin\n"
        "Translate 1 0 0\nRotate 90 0 0 1\nShape \"sphere\"\n");
    expectNear(d.camera.worldFromCamera.point({0, 0, 0}), {-5, -6, -7});
    expectNear(d.shapes[0].worldFromObject.point({1, 0, 0}), {1, 1, 0});
    SceneDescription l = parseSceneString("LookAt 0 0 0  0 0 -1  0 1 0\nCamera \"perspective\"\nWorldBegin");
    // Camera +x (image right) is world -x: pbrt's mirrored convention.
    expectNear(l.camera.worldFromCamera.vector({1, 0, 0}), {-1, 0, 0});
    expectNear(l.camera.worldFromCamera.vector({0, 0, 1}), {0, 0, -1});
}

TEST(Parser, AttributeScopesRestoreState) {
    setWarningsQuiet(true);
    SceneDescription d = parseSceneString(R"(WorldBegin
        AttributeBegin
          Translate 1 2 3
          ReverseOrientation
          Material "conductor"
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Shape "sphere"
        AttributeEnd
        Shape "disk"
        NamedMaterial "later"
        Shape "disk"
        MakeNamedMaterial "later" "string type" "dielectric"
    )");
    ASSERT_EQ(d.shapes.size(), 3u);
    EXPECT_TRUE(d.shapes[0].reverseOrientation);
    EXPECT_EQ(d.shapes[0].areaLight, 0);
    EXPECT_EQ(d.shapes[0].material.index, 1);
    EXPECT_FALSE(d.shapes[1].reverseOrientation);
    EXPECT_EQ(d.shapes[1].areaLight, -1);
    EXPECT_EQ(d.shapes[1].material.index, 0);
    expectNear(d.shapes[1].worldFromObject.point({0, 0, 0}), {0, 0, 0});
    EXPECT_EQ(d.shapes[2].material.name, "later");
    EXPECT_EQ(d.namedMaterials.at("later").type, "dielectric");
}

// ObjectBegin bakes its CTM; ObjectInstance's CTM applies on top.
TEST(Parser, Instancing) {
    setWarningsQuiet(true);
    SceneDescription d = parseSceneString(R"(WorldBegin
        ObjectBegin "o"
          Translate 1 0 0
          Shape "sphere"
        ObjectEnd
        Translate 0 5 0
        ObjectInstance "o"
    )");
    ASSERT_EQ(d.instances.at("o").shapes.size(), 1u);
    Transform world = d.instanceUses[0].worldFromInstance * d.instances.at("o").shapes[0].worldFromObject;
    expectNear(world.point({0, 0, 0}), {1, 5, 0});
    EXPECT_NE(errorOf("WorldBegin\nObjectBegin \"a\"\nObjectBegin \"b\""), "");
}

TEST(Parser, IncludeResolvesAgainstMainFileAndImportDoesNotLeak) {
    setWarningsQuiet(true);
    fs::path dir = fs::temp_directory_path() / ("pathspace-parse-" + std::to_string(getpid()));
    fs::create_directories(dir / "sub");
    std::ofstream(dir / "geom.pbrt") << "Shape \"sphere\"\n";
    std::ofstream(dir / "imp.pbrt") << "Translate 9 9 9\nMaterial \"conductor\"\nShape \"disk\"\n";
    std::ofstream(dir / "sub" / "main.pbrt") << "";
    std::ofstream(dir / "main.pbrt") << "WorldBegin\nInclude \"geom.pbrt\"\nImport \"imp.pbrt\"\nShape \"sphere\"\n";
    SceneDescription d = parseSceneFile((dir / "main.pbrt").string());
    ASSERT_EQ(d.shapes.size(), 3u);
    EXPECT_EQ(d.shapes[2].material.index, 0);
    expectNear(d.shapes[2].worldFromObject.point({0, 0, 0}), {0, 0, 0});
    // An include cycle is reported, not followed forever.
    std::ofstream(dir / "loop.pbrt") << "Include \"loop.pbrt\"\n";
    EXPECT_THROW(parseSceneFile((dir / "loop.pbrt").string()), InputError);
    fs::remove_all(dir);
}

TEST(Parser, UnusedParametersWarn) {
    setWarningsQuiet(true);
    SceneDescription d = parseSceneString("Film \"rgb\" \"float nonsense\" 3\nWorldBegin");
    int before = warningCount();
    d.film.params.getInt("xresolution", 1);
    d.film.params.reportUnused("Film");
    EXPECT_EQ(warningCount(), before + 1);
}

TEST(Spectra, ConversionsFollowPbrtNormalisation) {
    std::vector<float> l = {300, 900}, one = {1, 1};
    Spectrum white = sampledSpectrumToRGB(l, one, SpectrumKind::Albedo);
    EXPECT_NEAR(white.r, 1, 1e-3);
    EXPECT_NEAR(white.g, 1, 1e-3);
    EXPECT_NEAR(white.b, 1, 1e-3);
    // Emission spectra are normalised to luminance 1.
    Spectrum flat = sampledSpectrumToRGB(l, {10, 10}, SpectrumKind::Illuminant);
    EXPECT_NEAR(flat.luminance(), 1, 0.02);
    Spectrum bb = blackbodyToRGB(6500);
    EXPECT_NEAR(bb.luminance(), 1, 0.02);
    EXPECT_NEAR(bb.r / bb.b, 1, 0.1);  // 6500 K is close to the D65 white
    Spectrum warm = blackbodyToRGB(2700);
    EXPECT_GT(warm.r, warm.b * 2);
    auto cu = namedSpectrumToRGB("metal-Cu-eta", SpectrumKind::Unbounded);
    ASSERT_TRUE(cu.has_value());
    EXPECT_NEAR(cu->r, 0.2004f, 1e-3);
    EXPECT_FALSE(namedSpectrumToRGB("metal-Unobtainium-eta", SpectrumKind::Unbounded).has_value());
    // An albedo above 1 is an error, as in pbrt-v4; the same value is fine as emission.
    SceneDescription d = parseSceneString("WorldBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 2 0 0 ]\n");
    EXPECT_THROW(d.materials[1].params.getSpectrum("reflectance", SpectrumKind::Albedo), InputError);
    EXPECT_NO_THROW(d.materials[1].params.getSpectrum("reflectance", SpectrumKind::Illuminant));
}

// pbrt-v3 files in the shared scenes are refused with a message that says so.
TEST(Parser, SharedPbrtV3SceneIsRefusedClearly) {
    fs::path f = fs::path(PATHSPACE_SHARED_DIR) / "scenes/caustic-glass/glass.pbrt";
    if (!fs::exists(f)) GTEST_SKIP();
    try {
        parseSceneFile(f.string());
        FAIL() << "accepted a pbrt-v3 file";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("pbrt-v3"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("glass.pbrt:"), std::string::npos) << e.what();
    }
}
