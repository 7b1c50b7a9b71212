#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>

#include "scene/parser.h"
#include "shared_data.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

SceneDescription parse(const std::string& text) {
    setWarningsQuiet(true);
    return parseSceneString(text, ".", "s.pbrt");
}

std::string errorOf(const std::string& text) {
    setWarningsQuiet(true);
    try {
        parseSceneString(text, ".", "s.pbrt");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::string fileErrorOf(const fs::path& file) {
    setWarningsQuiet(true);
    try {
        parseSceneFile(file.string());
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// The error names the place and the offending text.
void expectError(const std::string& text, const std::string& where, const std::string& token) {
    std::string e = errorOf(text);
    EXPECT_NE(e.find(where + ": error: "), std::string::npos) << "for: " << text << "\ngot: " << e;
    EXPECT_NE(e.find(token), std::string::npos) << "for: " << text << "\ngot: " << e;
}

void expectNear(Vec3 a, Vec3 b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

class TempDir {
public:
    TempDir() {
        static int n = 0;
        path = fs::temp_directory_path() / ("pathspace-parser-" + std::to_string(getpid()) + "-" + std::to_string(n++));
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    fs::path write(const std::string& name, const std::string& text) const {
        fs::path p = path / name;
        fs::create_directories(p.parent_path());
        std::ofstream(p) << text;
        return p;
    }
    fs::path path;
};

}  // namespace

TEST(Parser, Defaults) {
    SceneDescription d = parse("WorldBegin\nShape \"sphere\"");
    EXPECT_EQ(d.camera.type, "perspective");
    EXPECT_EQ(d.film.type, "rgb");
    EXPECT_EQ(d.sampler.type, "zsobol");
    EXPECT_EQ(d.integrator.type, "volpath");
    EXPECT_EQ(d.filter.type, "gaussian");
    EXPECT_FALSE(d.cameraGiven);
    EXPECT_TRUE(d.camera.worldFromCamera.isIdentity());
    ASSERT_EQ(d.materials.size(), 1u);
    EXPECT_EQ(d.materials[0].type, "diffuse");
    EXPECT_TRUE(d.materials[0].params.params.empty());
    ASSERT_EQ(d.shapes.size(), 1u);
    EXPECT_EQ(d.shapes[0].material.index, 0);
    EXPECT_EQ(d.shapes[0].areaLight, -1);
    EXPECT_FALSE(d.shapes[0].reverseOrientation);
    EXPECT_EQ(d.sceneFile, "s.pbrt");
    EXPECT_EQ(d.baseDirectory, ".");
}

TEST(Parser, EveryDirective) {
    SceneDescription d = parse(R"(
        Option "seed" 5
        Option "disable-pixel-jitter" true
        Option "rendercoordsys" "world"
        ColorSpace "srgb"
        Identity
        LookAt 0 0 5  0 0 0  0 1 0
        CoordinateSystem "mine"
        Camera "orthographic" "float screenwindow" [ -1 1 -1 1 ]
        Film "rgb" "integer xresolution" 64 "integer yresolution" [ 32 ] "string filename" "x.exr"
        Sampler "independent" "integer pixelsamples" 4
        Integrator "path" "integer maxdepth" 3
        PixelFilter "box" "float xradius" 0.5
        Accelerator "bvh"
        Attribute "shape" "float radius" 2
        WorldBegin
        AttributeBegin
          CoordSysTransform "mine"
          Material "conductor" "spectrum eta" "metal-Au-eta"
          Texture "checks" "spectrum" "checkerboard" "float uscale" 4
          Texture "checks" "float" "constant" "float value" 0.5
          MakeNamedMaterial "red" "string type" "diffuse" "rgb reflectance" [ 0.8 0.1 0.1 ]
          LightSource "point" "rgb I" [ 1 1 1 ]
          AreaLightSource "diffuse" "rgb L" [ 2 2 2 ]
          ReverseOrientation
          Shape "sphere"
          NamedMaterial "red"
          Shape "disk" "float radius" 3
        AttributeEnd
        Translate 1 0 0
        Scale 2 2 2
        Rotate 90 0 0 1
        ConcatTransform [ 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1 ]
        Transform [ 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1 ]
        ObjectBegin "thing"
          Shape "trianglemesh" "point3 P" [ 0 0 0 1 0 0 0 1 0 ]
        ObjectEnd
        ObjectInstance "thing"
    )");
    EXPECT_EQ(d.options.at("seed"), "5");
    EXPECT_EQ(d.options.at("disablepixeljitter"), "true");
    EXPECT_EQ(d.options.at("rendercoordsys"), "world");
    EXPECT_TRUE(d.cameraGiven);
    EXPECT_EQ(d.camera.type, "orthographic");
    EXPECT_EQ(d.camera.params.getFloats("screenwindow").size(), 4u);
    EXPECT_EQ(d.camera.loc.line, 9);
    EXPECT_EQ(d.film.params.getInt("xresolution", 0), 64);
    EXPECT_EQ(d.film.params.getInt("yresolution", 0), 32);
    EXPECT_EQ(d.sampler.type, "independent");
    EXPECT_EQ(d.integrator.params.getInt("maxdepth", 0), 3);
    EXPECT_EQ(d.filter.type, "box");

    ASSERT_EQ(d.materials.size(), 2u);
    EXPECT_EQ(d.materials[1].type, "conductor");
    ASSERT_EQ(d.namedMaterials.count("red"), 1u);
    const MaterialEntity& red = d.namedMaterials.at("red");
    EXPECT_EQ(red.type, "diffuse");
    EXPECT_EQ(red.name, "red");
    EXPECT_FALSE(red.params.has("type"));  // the class, not a parameter
    ASSERT_EQ(d.spectrumTextures.size(), 1u);
    ASSERT_EQ(d.floatTextures.size(), 1u);  // float and spectrum names are separate
    EXPECT_EQ(d.spectrumTextures[0].type, "checkerboard");
    EXPECT_FALSE(d.spectrumTextures[0].isFloat);
    EXPECT_TRUE(d.floatTextures[0].isFloat);
    ASSERT_EQ(d.lights.size(), 1u);
    EXPECT_EQ(d.lights[0].type, "point");
    ASSERT_EQ(d.areaLights.size(), 1u);

    ASSERT_EQ(d.shapes.size(), 2u);
    const ShapeEntity& sphere = d.shapes[0];
    EXPECT_EQ(sphere.material.index, 1);
    EXPECT_EQ(sphere.areaLight, 0);
    EXPECT_TRUE(sphere.reverseOrientation);
    // Attribute defaults: supplied, marked, and overridden by explicit parameters.
    EXPECT_FLOAT_EQ(sphere.params.getFloat("radius", 0), 2.0f);
    EXPECT_TRUE(sphere.params.find("radius")->fromAttribute);
    EXPECT_FLOAT_EQ(d.shapes[1].params.getFloat("radius", 0), 3.0f);
    EXPECT_EQ(d.shapes[1].material.index, -1);
    EXPECT_EQ(d.shapes[1].material.name, "red");
    // CoordSysTransform "mine" restored the camera-from-world of the options block.
    expectNear(sphere.worldFromObject.point({0, 0, 0}), {0, 0, 5});

    ASSERT_EQ(d.instances.count("thing"), 1u);
    EXPECT_EQ(d.instances.at("thing").shapes.size(), 1u);
    ASSERT_EQ(d.instanceUses.size(), 1u);
    EXPECT_TRUE(d.instanceUses[0].worldFromInstance.isIdentity());  // after Transform [identity]
}

TEST(Parser, IgnoredDirectivesOnlyWarn) {
    SceneDescription d = parse(R"(
        TransformTimes 0 1
        ActiveTransform StartTime
        ColorSpace "rec2020"
        WorldBegin
        MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 1 1 1 ]
        MediumInterface "" "fog"
        MediumInterface "fog"
        TransformBegin
          Shape "sphere"
        TransformEnd
    )");
    EXPECT_EQ(d.shapes.size(), 1u);
}

// The CTM is post-multiplied; Transform lists the matrix column by column (§1).
TEST(Parser, TransformSemantics) {
    SceneDescription d = parse(
        "Transform [ 1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1 ]\nCamera \"perspective\"\nWorldBegin\n"
        "Translate 1 0 0\nRotate 90 0 0 1\nShape \"sphere\"\n"
        "Identity\nTranslate 1 0 0\nConcatTransform [ 2 0 0 0  0 2 0 0  0 0 2 0  0 0 0 1 ]\nShape \"sphere\"\n"
        "Identity\nScale 2 1 1\nTranslate 1 0 0\nShape \"sphere\"\n");
    // The camera CTM (translation 5,6,7) is camera-from-world: its inverse is stored.
    expectNear(d.camera.worldFromCamera.point({0, 0, 0}), {-5, -6, -7});
    ASSERT_EQ(d.shapes.size(), 3u);
    expectNear(d.shapes[0].worldFromObject.point({1, 0, 0}), {1, 1, 0});   // T * R
    expectNear(d.shapes[1].worldFromObject.point({1, 0, 0}), {3, 0, 0});   // T * S
    expectNear(d.shapes[2].worldFromObject.point({0, 0, 0}), {2, 0, 0});   // S * T
    // The inverse is kept in step.
    expectNear(d.shapes[0].worldFromObject.inverse().point({1, 1, 0}), {1, 0, 0});
}

// LookAt's mirrored frame (§1): looking down -z with +y up, camera +x is world -x.
TEST(Parser, LookAtGivesPbrtsMirroredFrame) {
    SceneDescription l = parse("LookAt 0 0 0  0 0 -1  0 1 0\nCamera \"perspective\"\nWorldBegin");
    expectNear(l.camera.worldFromCamera.vector({1, 0, 0}), {-1, 0, 0});
    expectNear(l.camera.worldFromCamera.vector({0, 1, 0}), {0, 1, 0});
    expectNear(l.camera.worldFromCamera.vector({0, 0, 1}), {0, 0, -1});
    SceneDescription e = parse("LookAt 1 2 3  1 2 10  0 1 0\nCamera \"perspective\"\nWorldBegin");
    expectNear(e.camera.worldFromCamera.point({0, 0, 0}), {1, 2, 3});
    expectNear(e.camera.worldFromCamera.vector({1, 0, 0}), {1, 0, 0});
    // The usual fix for scenes from right-handed tools: Scale -1 1 1 before LookAt.
    SceneDescription m = parse("Scale -1 1 1\nLookAt 0 0 0  0 0 -1  0 1 0\nCamera \"perspective\"\nWorldBegin");
    expectNear(m.camera.worldFromCamera.vector({1, 0, 0}), {1, 0, 0});
    EXPECT_TRUE(m.camera.worldFromCamera.swapsHandedness());
}

TEST(Parser, NamedCoordinateSystems) {
    SceneDescription d = parse(R"(
        LookAt 0 0 5  0 0 0  0 1 0
        Camera "perspective"
        WorldBegin
        Translate 3 0 0
        CoordinateSystem "shifted"
        CoordSysTransform "camera"
        Shape "sphere"
        CoordSysTransform "world"
        Shape "sphere"
        CoordSysTransform "shifted"
        Shape "sphere"
        CoordSysTransform "nonexistent"
        Shape "sphere"
    )");
    ASSERT_EQ(d.shapes.size(), 4u);
    expectNear(d.shapes[0].worldFromObject.point({0, 0, 0}), {0, 0, 5});  // at the camera
    expectNear(d.shapes[1].worldFromObject.point({0, 0, 0}), {0, 0, 0});
    expectNear(d.shapes[2].worldFromObject.point({0, 0, 0}), {3, 0, 0});
    expectNear(d.shapes[3].worldFromObject.point({0, 0, 0}), {3, 0, 0});  // unknown: warning, unchanged
}

// Motion (pbrt-v4's semantics): the CTM has a start and an end keyframe; ActiveTransform picks
// which ones transform directives change, AttributeEnd restores the choice, CoordSysTransform
// restores both keyframes whatever is active, and TransformTimes (options block) dates them.
TEST(Parser, MotionKeepsBothTransformKeyframes) {
    SceneDescription d = parse(R"(TransformTimes 0.25 2
        LookAt 0 0 0  0 0 1  0 1 0
        ActiveTransform EndTime
        Translate 0 0 -3
        ActiveTransform All
        Camera "perspective"
        WorldBegin
        Translate 1 0 0
        CoordinateSystem "one"
        AttributeBegin
          ActiveTransform EndTime
          Translate 5 0 0
          Shape "sphere"
        AttributeEnd
        Translate 1 0 0
        Shape "sphere"
        ActiveTransform StartTime
        CoordSysTransform "one"
        Shape "sphere"
        ObjectBegin "o"
        Shape "sphere"
        ObjectEnd
        ActiveTransform EndTime
        Translate 0 2 0
        ObjectInstance "o"
    )");
    EXPECT_EQ(d.transformStartTime, 0.25f);
    EXPECT_EQ(d.transformEndTime, 2.0f);
    EXPECT_EQ(d.camera.transformStartTime, 0.25f);
    expectNear(d.camera.worldFromCamera.point({0, 0, 0}), {0, 0, 0});
    expectNear(d.camera.worldFromCameraEnd.point({0, 0, 0}), {0, 0, 3});  // CTM = camera-from-world
    ASSERT_EQ(d.shapes.size(), 3u);
    expectNear(d.shapes[0].worldFromObject.point({0, 0, 0}), {1, 0, 0});
    expectNear(d.shapes[0].worldFromObjectEnd.point({0, 0, 0}), {6, 0, 0});
    // After AttributeEnd both keyframes are active again and equal.
    expectNear(d.shapes[1].worldFromObject.point({0, 0, 0}), {2, 0, 0});
    expectNear(d.shapes[1].worldFromObjectEnd.point({0, 0, 0}), {2, 0, 0});
    expectNear(d.shapes[2].worldFromObjectEnd.point({0, 0, 0}), {1, 0, 0});
    ASSERT_EQ(d.instanceUses.size(), 1u);
    expectNear(d.instanceUses[0].worldFromInstance.point({0, 0, 0}), {1, 0, 0});
    expectNear(d.instanceUses[0].worldFromInstanceEnd.point({0, 0, 0}), {1, 2, 0});
    // A moving area light is an error in pbrt-v4; TransformTimes belongs before WorldBegin.
    expectError("WorldBegin\nActiveTransform EndTime Translate 1 0 0 ActiveTransform All\n"
                "AreaLightSource \"diffuse\"\nShape \"sphere\"",
                "s.pbrt:4:1", "moving area lights are not supported");
    expectError("WorldBegin\nTransformTimes 0 1", "s.pbrt:2:1", "TransformTimes");
}

TEST(Parser, AttributeScopesRestoreState) {
    SceneDescription d = parse(R"(WorldBegin
        Attribute "shape" "float radius" 5
        AttributeBegin
          Translate 1 2 3
          ReverseOrientation
          Material "conductor"
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Attribute "shape" "float radius" 7 "float zmax" 0.5
          Shape "sphere"
          AttributeBegin
            NamedMaterial "inner"
            Shape "sphere"
          AttributeEnd
          Shape "sphere"
        AttributeEnd
        Shape "disk"
        NamedMaterial "later"
        Shape "disk"
        MakeNamedMaterial "later" "string type" "dielectric"
        MakeNamedMaterial "inner" "string type" "diffuse"
    )");
    ASSERT_EQ(d.shapes.size(), 5u);
    const ShapeEntity& in = d.shapes[0];
    EXPECT_TRUE(in.reverseOrientation);
    EXPECT_EQ(in.areaLight, 0);
    EXPECT_EQ(in.material.index, 1);
    EXPECT_FLOAT_EQ(in.params.getFloat("radius", 0), 7.0f);
    EXPECT_FLOAT_EQ(in.params.getFloat("zmax", 0), 0.5f);
    expectNear(in.worldFromObject.point({0, 0, 0}), {1, 2, 3});
    EXPECT_EQ(d.shapes[1].material.name, "inner");
    EXPECT_EQ(d.shapes[1].areaLight, 0);
    EXPECT_EQ(d.shapes[2].material.index, 1);  // restored after the inner block
    const ShapeEntity& out = d.shapes[3];
    EXPECT_FALSE(out.reverseOrientation);
    EXPECT_EQ(out.areaLight, -1);
    EXPECT_EQ(out.material.index, 0);
    EXPECT_FLOAT_EQ(out.params.getFloat("radius", 0), 5.0f);
    EXPECT_FALSE(out.params.has("zmax"));
    expectNear(out.worldFromObject.point({0, 0, 0}), {0, 0, 0});
    EXPECT_EQ(d.shapes[4].material.name, "later");  // resolved after parsing
    EXPECT_EQ(d.namedMaterials.at("later").type, "dielectric");
}

TEST(Parser, AttributeDefaultsForEveryTarget) {
    SceneDescription d = parse(R"(WorldBegin
        Attribute "light" "float scale" 3
        Attribute "material" "float roughness" 0.2
        Attribute "texture" "float uscale" 8
        Attribute "medium" "float g" 0.1
        LightSource "point"
        AreaLightSource "diffuse"
        Material "conductor" "float roughness" 0.4
        MakeNamedMaterial "m" "string type" "diffuse"
        Texture "t" "float" "checkerboard"
    )");
    EXPECT_FLOAT_EQ(d.lights[0].params.getFloat("scale", 1), 3.0f);
    EXPECT_FLOAT_EQ(d.areaLights[0].params.getFloat("scale", 1), 3.0f);
    EXPECT_FLOAT_EQ(d.materials[1].params.getFloat("roughness", 0), 0.4f);
    EXPECT_FLOAT_EQ(d.namedMaterials.at("m").params.getFloat("roughness", 0), 0.2f);
    EXPECT_FLOAT_EQ(d.floatTextures[0].params.getFloat("uscale", 1), 8.0f);
    // Defaults never count as unused.
    int before = warningCount();
    d.namedMaterials.at("m").params.reportUnused("unique context: attribute defaults");
    EXPECT_EQ(warningCount(), before);
    EXPECT_NE(errorOf("WorldBegin\nAttribute \"camera\" \"float fov\" 3"), "");
}

TEST(Parser, TexturesKeepTheirTransform) {
    SceneDescription d = parse(R"(WorldBegin
        Translate 0 0 4
        Texture "grid" "spectrum" "checkerboard" "string mapping" "planar" "texture tex1" "other"
    )");
    ASSERT_EQ(d.spectrumTextures.size(), 1u);
    const TextureEntity& t = d.spectrumTextures[0];
    EXPECT_EQ(t.name, "grid");
    expectNear(t.worldFromTexture.point({0, 0, 0}), {0, 0, 4});
    EXPECT_EQ(t.params.getTexture("tex1"), "other");
}

// ObjectBegin bakes its CTM; ObjectInstance's CTM applies on top (§8 Instancing).
TEST(Parser, Instancing) {
    SceneDescription d = parse(R"(WorldBegin
        Translate 0 0 100
        ObjectBegin "o"
          Translate 1 0 0
          Shape "sphere"
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Shape "sphere"
        ObjectEnd
        Shape "disk"
        Identity
        Translate 0 5 0
        ObjectInstance "o"
        ObjectInstance "o"
    )");
    const InstanceDefinition& def = d.instances.at("o");
    ASSERT_EQ(def.shapes.size(), 2u);
    EXPECT_EQ(def.name, "o");
    EXPECT_EQ(def.shapes[1].areaLight, -1);  // area lights in instances: warning, not emissive
    Transform world = d.instanceUses[0].worldFromInstance * def.shapes[0].worldFromObject;
    expectNear(world.point({0, 0, 0}), {1, 5, 100});
    EXPECT_EQ(d.instanceUses.size(), 2u);
    // ObjectEnd restores the state in effect at ObjectBegin.
    ASSERT_EQ(d.shapes.size(), 1u);
    expectNear(d.shapes[0].worldFromObject.point({0, 0, 0}), {0, 0, 100});
    EXPECT_EQ(d.areaLights.size(), 1u);
    EXPECT_EQ(d.shapes[0].areaLight, -1);
}

TEST(Parser, InstancingErrors) {
    expectError("WorldBegin\nObjectBegin \"a\"\n  ObjectBegin \"b\"\n", "s.pbrt:3:3", "ObjectBegin");
    expectError("WorldBegin\nObjectBegin \"a\"\nObjectEnd\nObjectBegin \"a\"\n", "s.pbrt:4:1", "\"a\"");
    expectError("WorldBegin\nObjectEnd\n", "s.pbrt:2:1", "ObjectEnd");
    expectError("WorldBegin\nObjectBegin \"a\"\nObjectInstance \"a\"\n", "s.pbrt:3:1", "ObjectInstance");
    expectError("WorldBegin\nObjectInstance \"nowhere\"\n", "s.pbrt:2:1", "nowhere");
    expectError("WorldBegin\nObjectBegin \"a\"\n", "s.pbrt:2:1", "ObjectEnd");
    expectError("WorldBegin\nObjectBegin \"a\"\nAttributeBegin\nObjectEnd\n", "s.pbrt:4:1", "AttributeBegin");
    expectError("WorldBegin\nAttributeBegin\nObjectBegin \"a\"\nAttributeEnd\n", "s.pbrt:4:1", "ObjectBegin");
    // A use before the definition is fine: names are resolved at the end.
    EXPECT_EQ(errorOf("WorldBegin\nObjectInstance \"a\"\nObjectBegin \"a\"\nObjectEnd\n"), "");
}

TEST(Parser, IncludeResolvesAgainstTheMainFile) {
    TempDir dir;
    dir.write("geom.pbrt", "Shape \"sphere\"\n");
    // sub/level1.pbrt includes "geom.pbrt": relative to the main file, not to sub/.
    dir.write("sub/level1.pbrt", "Translate 0 1 0\nInclude \"geom.pbrt\"\n");
    dir.write("sub/geom.pbrt", "Shape \"disk\"\n");
    fs::path main = dir.write("main.pbrt", "WorldBegin\nInclude \"sub/level1.pbrt\"\nShape \"cylinder\"\n");
    SceneDescription d = parseSceneFile(main.string());
    EXPECT_EQ(d.sceneFile, main.string());
    EXPECT_EQ(d.baseDirectory, dir.path.string());
    ASSERT_EQ(d.shapes.size(), 2u);
    EXPECT_EQ(d.shapes[0].type, "sphere");
    EXPECT_EQ(d.shapes[0].loc.file, (dir.path / "geom.pbrt").string());
    EXPECT_EQ(d.shapes[0].loc.line, 1);
    // Include shares the graphics state.
    expectNear(d.shapes[1].worldFromObject.point({0, 0, 0}), {0, 1, 0});
    // Include is allowed in the options block too, and a gzipped file name is just a file.
    dir.write("cam.pbrt", "Camera \"orthographic\"\n");
    fs::path m2 = dir.write("m2.pbrt", "Include \"cam.pbrt\"\nWorldBegin\n");
    EXPECT_EQ(parseSceneFile(m2.string()).camera.type, "orthographic");
}

TEST(Parser, ImportDoesNotLeakState) {
    TempDir dir;
    dir.write("imp.pbrt",
              "Translate 9 9 9\nMaterial \"conductor\"\nReverseOrientation\nAreaLightSource \"diffuse\"\n"
              "Shape \"disk\"\nMakeNamedMaterial \"fromimport\" \"string type\" \"diffuse\"\n"
              "ObjectBegin \"obj\"\nShape \"sphere\"\nObjectEnd\nCoordinateSystem \"leaked\"\n"
              "Attribute \"shape\" \"float radius\" 9\nCoordSysTransform \"camera\"\n");
    fs::path main = dir.write("main.pbrt",
                              "WorldBegin\nTranslate 1 0 0\nImport \"imp.pbrt\"\nShape \"sphere\"\n"
                              "ObjectInstance \"obj\"\nCoordSysTransform \"leaked\"\nShape \"sphere\"\n");
    SceneDescription d = parseSceneFile(main.string());
    ASSERT_EQ(d.shapes.size(), 3u);
    const ShapeEntity& imported = d.shapes[0];
    EXPECT_TRUE(imported.reverseOrientation);
    EXPECT_EQ(imported.areaLight, 0);
    // The import started from a copy of the state (Translate 1 0 0), and pbrt-v4 gives it
    // no named coordinate systems, so CoordSysTransform "camera" there did nothing.
    expectNear(imported.worldFromObject.point({0, 0, 0}), {10, 9, 9});
    const ShapeEntity& after = d.shapes[1];
    EXPECT_FALSE(after.reverseOrientation);
    EXPECT_EQ(after.areaLight, -1);
    EXPECT_EQ(after.material.index, 0);
    EXPECT_FALSE(after.params.has("radius"));
    expectNear(after.worldFromObject.point({0, 0, 0}), {1, 0, 0});
    expectNear(d.shapes[2].worldFromObject.point({0, 0, 0}), {1, 0, 0});  // "leaked" is unknown
    // Entities it defines are global.
    EXPECT_EQ(d.namedMaterials.count("fromimport"), 1u);
    EXPECT_EQ(d.instances.count("obj"), 1u);
    EXPECT_EQ(d.materials.size(), 2u);

    // Its blocks must close inside it; Import belongs to the world block.
    dir.write("open.pbrt", "AttributeBegin\n");
    fs::path bad = dir.write("bad.pbrt", "WorldBegin\nImport \"open.pbrt\"\n");
    std::string e = fileErrorOf(bad);
    EXPECT_NE(e.find((dir.path / "open.pbrt").string() + ":1:1"), std::string::npos) << e;
    fs::path early = dir.write("early.pbrt", "Import \"imp.pbrt\"\nWorldBegin\n");
    e = fileErrorOf(early);
    EXPECT_NE(e.find("early.pbrt:1:1: error: Import"), std::string::npos) << e;
}

TEST(Parser, ImportInsideObjectBeginAddsToTheDefinition) {
    TempDir dir;
    dir.write("part.pbrt", "Shape \"sphere\"\n");
    dir.write("closer.pbrt", "ObjectEnd\n");
    fs::path main = dir.write("main.pbrt", "WorldBegin\nObjectBegin \"o\"\nImport \"part.pbrt\"\nObjectEnd\n");
    SceneDescription d = parseSceneFile(main.string());
    EXPECT_EQ(d.instances.at("o").shapes.size(), 1u);
    EXPECT_TRUE(d.shapes.empty());
    fs::path bad = dir.write("bad.pbrt", "WorldBegin\nObjectBegin \"o\"\nImport \"closer.pbrt\"\nObjectEnd\n");
    EXPECT_NE(fileErrorOf(bad).find("closer.pbrt:1:1"), std::string::npos) << fileErrorOf(bad);
}

TEST(Parser, IncludeErrors) {
    expectError("WorldBegin\n  Include \"does-not-exist.pbrt\"\n", "s.pbrt:2:3", "does-not-exist.pbrt");
    TempDir dir;
    dir.write("a.pbrt", "WorldBegin\nInclude \"b.pbrt\"\n");
    dir.write("b.pbrt", "Include \"a.pbrt\"\n");
    std::string e = fileErrorOf(dir.path / "a.pbrt");
    EXPECT_NE(e.find((dir.path / "b.pbrt").string() + ":1:1: error: Include"), std::string::npos) << e;
    EXPECT_NE(e.find("cycle"), std::string::npos) << e;
    dir.write("self.pbrt", "WorldBegin\nImport \"self.pbrt\"\n");
    EXPECT_NE(fileErrorOf(dir.path / "self.pbrt").find("cycle"), std::string::npos);
    // A long chain of distinct files stops at the depth limit.
    for (int i = 0; i < 80; ++i) dir.write("chain" + std::to_string(i) + ".pbrt", "Include \"chain" + std::to_string(i + 1) + ".pbrt\"\n");
    dir.write("chain80.pbrt", "WorldBegin\n");
    e = fileErrorOf(dir.path / "chain0.pbrt");
    EXPECT_NE(e.find("deep"), std::string::npos) << e;
    // The same file twice in sequence is not a cycle.
    dir.write("twice.pbrt", "WorldBegin\nInclude \"geom.pbrt\"\nInclude \"geom.pbrt\"\n");
    dir.write("geom.pbrt", "Shape \"sphere\"\n");
    EXPECT_EQ(parseSceneFile((dir.path / "twice.pbrt").string()).shapes.size(), 2u);
}

// Every error names file:line:column and the offending token.
TEST(Parser, ErrorMessagesNamePlaceAndToken) {
    expectError("WorldBegin\nShape \"sphere\" \"float radius [ 1 ]\n", "s.pbrt:2:16", "\"float radius [ 1 ]");
    expectError("WorldBegin\n  Frobnicate 3\n", "s.pbrt:2:3", "Frobnicate");
    expectError("WorldBegin\nWorldEnd\n", "s.pbrt:2:1", "WorldEnd");
    expectError("Film \"rgb\" \"bool x\" \"true\"\nWorldBegin", "s.pbrt:1:21", "\"true\"");
    expectError("Film \"rgb\" \"bool x\" yes\nWorldBegin", "s.pbrt:1:21", "yes");
    expectError("Film \"rgb\" \"integer xresolution\" [ 2.0 ]\nWorldBegin", "s.pbrt:1:36", "2.0");
    expectError("Translate [ 1 2 3 ]\nWorldBegin", "s.pbrt:1:11", "[");
    expectError("WorldBegin\nCamera \"perspective\"", "s.pbrt:2:1", "Camera");
    expectError("Shape \"sphere\"\nWorldBegin", "s.pbrt:1:1", "Shape");
    expectError("WorldBegin\nTranslate 1 nan 3", "s.pbrt:2:13", "nan");
    expectError("WorldBegin\nTranslate 1 inf 3", "s.pbrt:2:13", "inf");
    expectError("WorldBegin\nShape \"sphere\" \"float radius\" 1e999", "s.pbrt:2:31", "1e999");
    expectError("WorldBegin\nShape \"sphere\" \"float radius\" 1e39", "s.pbrt:2:31", "1e39");
    expectError("WorldBegin\nShape \"sphere\" \"integer n\" 99999999999", "s.pbrt:2:28", "99999999999");
    expectError("WorldBegin\nTranslate 1 2", "s.pbrt:2:1", "Translate");
    expectError("WorldBegin\nShape \"sphere\" \"float radius\" [ 1 2", "s.pbrt:2:31", "float radius");
    expectError("WorldBegin\nShape \"sphere\" \"float radius\" [ ]", "s.pbrt:2:16", "float radius");
    expectError("WorldBegin\nShape \"sphere\" \"float radius\" \"one\"", "s.pbrt:2:31", "\"one\"");
    expectError("WorldBegin\nShape \"sphere\" \"string s\" 3", "s.pbrt:2:27", "3");
    expectError("WorldBegin\nShape \"sphere\" \"radius\" 3", "s.pbrt:2:16", "\"radius\"");
    expectError("WorldBegin\nShape \"sphere\" \"float\" 3", "s.pbrt:2:16", "\"float\"");
    expectError("WorldBegin\nShape \"sphere\" \"quaternion q\" 3", "s.pbrt:2:16", "quaternion");
    expectError("WorldBegin\nShape sphere", "s.pbrt:2:7", "sphere");
    expectError("WorldBegin\nShape", "s.pbrt:2:1", "Shape");
    expectError("Transform [ 1 0 0 0 ]\nWorldBegin", "s.pbrt:1:21", "]");
    expectError("Transform 1 0 0 0\nWorldBegin", "s.pbrt:1:11", "1");
    expectError("LookAt 0 0 0 0 0 0 0 1 0\nWorldBegin", "s.pbrt:1:1", "LookAt");
    expectError("WorldBegin\nWorldBegin", "s.pbrt:2:1", "WorldBegin");
    expectError("WorldBegin\n\"stray\"", "s.pbrt:2:1", "\"stray\"");
    expectError("WorldBegin\n]", "s.pbrt:2:1", "]");
    expectError("Option \"bool disablepixeljitter\" true\nWorldBegin", "s.pbrt:1:1", "bool disablepixeljitter");
    expectError("Option \"nosuchoption\" 3\nWorldBegin", "s.pbrt:1:1", "nosuchoption");
    expectError("Option \"disablepixeljitter\" \"true\"\nWorldBegin", "s.pbrt:1:1", "\"true\"");
    expectError("ActiveTransform Sometimes\nWorldBegin", "s.pbrt:1:17", "Sometimes");
    expectError("WorldBegin\nTexture \"t\" \"vector\" \"constant\"", "s.pbrt:2:1", "vector");
    expectError("WorldBegin\nTexture \"t\" \"float\" \"constant\"\nTexture \"t\" \"float\" \"constant\"", "s.pbrt:3:1", "\"t\"");
    expectError("WorldBegin\nMakeNamedMaterial \"m\" \"float roughness\" 1", "s.pbrt:2:1", "string type");
    expectError("WorldBegin\nMakeNamedMaterial \"m\" \"string type\" \"diffuse\"\nMakeNamedMaterial \"m\" \"string type\" \"diffuse\"",
                "s.pbrt:3:1", "\"m\"");
    expectError("WorldBegin\nAttributeBegin\n", "s.pbrt:2:1", "AttributeBegin");
    expectError("Camera \"perspective\"\n", "s.pbrt", "WorldBegin");
    expectError("WorldBegin\nShape \"sphere\" \"spectrum s\" [ 400 \"x\" ]", "s.pbrt:2:35", "\"x\"");
    expectError("WorldBegin\nShape \"sphere\" \"float radius\" [ 1 [ 2 ] ]", "s.pbrt:2:35", "[");
}

// pbrt-v3 syntax is refused with a message that says so and suggests the upgrade.
// pbrt-v4 accepts a singular or non-finite CTM (its inverse becomes NaN): only an object
// placed under it is an error, located at that object and naming the directive to blame.
TEST(Parser, SingularTransformsAreAnErrorOnlyUnderAnObject) {
    const std::string singular[] = {"ConcatTransform [ 1 0 0 0  0 1 0 0  0 0 0 0  0 0 0 1 ]",
                                    "Transform [ 0 0 0 0  0 0 0 0  0 0 0 0  0 0 0 0 ]", "Scale 0 1 1", "Rotate 10 0 0 0"};
    for (const std::string& t : singular) {
        // In a block without shapes (transparent-machines does this): accepted.
        SceneDescription d = parse("WorldBegin\nAttributeBegin\n  " + t + "\nAttributeEnd\nShape \"sphere\"\n");
        EXPECT_EQ(d.shapes.size(), 1u) << t;
        EXPECT_TRUE(d.shapes[0].worldFromObject.isInvertible()) << t;
        // Replaced before use: accepted.
        EXPECT_EQ(parse("WorldBegin\n" + t + "\nIdentity\nShape \"sphere\"\n").shapes.size(), 1u) << t;
        EXPECT_EQ(parse("WorldBegin\n" + t + "\nTransform [ 2 0 0 0  0 2 0 0  0 0 2 0  0 0 0 1 ]\nShape \"sphere\"\n").shapes.size(), 1u) << t;
        // Under it: a shape, a light, an instance, the camera, each located at its own
        // directive; the message names the directive that made the transform singular.
        const std::string directive = t.substr(0, t.find(' '));
        for (const std::string& obj : {std::string("Shape \"sphere\""), std::string("LightSource \"point\""),
                                       std::string("ObjectInstance \"o\"")}) {
            std::string e = errorOf("WorldBegin\nObjectBegin \"o\"\nObjectEnd\nTranslate 1 2 3\n" + t + "\nTranslate 1 0 0\n  " + obj + "\n");
            EXPECT_NE(e.find("s.pbrt:7:3: error: " + obj.substr(0, obj.find(' ')) + ": the current transform is singular"), std::string::npos) << e;
            EXPECT_NE(e.find("since " + directive + " at s.pbrt:5:1"), std::string::npos) << e;
        }
        expectError(t + "\nCamera \"perspective\"\nWorldBegin\n", "s.pbrt:2:1", "since " + directive + " at s.pbrt:1:1");
        // A shape inside an object definition under a singular transform.
        expectError("WorldBegin\nObjectBegin \"o\"\n" + t + "\nShape \"sphere\"\nObjectEnd\n", "s.pbrt:4:1", "singular");
    }
    // A named coordinate system keeps the singular transform; restoring it is named.
    expectError("WorldBegin\nScale 0 0 0\nCoordinateSystem \"flat\"\nIdentity\nCoordSysTransform \"flat\"\nShape \"sphere\"\n",
                "s.pbrt:6:1", "since CoordSysTransform at s.pbrt:5:1");
    // An invertible product stays usable: Scale 2 then Scale 0.5 is the identity.
    EXPECT_TRUE(parse("WorldBegin\nScale 2 2 2\nScale 0.5 0.5 0.5\nShape \"sphere\"\n").shapes[0].worldFromObject.isIdentity());
}

TEST(Parser, PbrtV3SyntaxIsRefused) {
    auto expectV3 = [](const std::string& text, const std::string& where) {
        std::string e = errorOf(text);
        EXPECT_NE(e.find("pbrt-v3"), std::string::npos) << text << "\n" << e;
        EXPECT_NE(e.find("pbrt --upgrade"), std::string::npos) << text << "\n" << e;
        EXPECT_NE(e.find(where), std::string::npos) << text << "\n" << e;
    };
    expectV3("WorldBegin\nWorldEnd", "s.pbrt:2:1");
    expectV3("Film \"image\"\nWorldBegin", "s.pbrt:1:1");
    for (const char* m : {"matte", "plastic", "glass", "uber", "metal", "mirror", "substrate", "translucent"}) {
        expectV3(std::string("WorldBegin\nMaterial \"") + m + "\"", "s.pbrt:2:1");
        expectV3(std::string("WorldBegin\nMakeNamedMaterial \"x\" \"string type\" \"") + m + "\"", "s.pbrt:2:1");
    }
    for (const char* t : {"normal3", "point", "vector", "color"})
        expectV3(std::string("WorldBegin\nShape \"x\" \"") + t + " n\" [ 1 2 3 ]", "s.pbrt:2:11");
    expectV3("WorldBegin\nShape \"x\" \"bool b\" \"true\"", "s.pbrt:2:20");
    expectV3("WorldBegin\nMaterial \"dielectric\" \"float index\" 1.5", "s.pbrt:2:23");
    expectV3("WorldBegin\nLightSource \"spot\" \"blackbody I\" [ 5500 125 ]", "s.pbrt:2:20");
    expectV3("WorldBegin\nTexture \"t\" \"color\" \"constant\"", "s.pbrt:2:1");
}

TEST(Parser, NumbersAndValues) {
    SceneDescription d = parse(R"(WorldBegin
        Shape "x" "float a" [ 1 -2.5 +3 .5 1e2 -1E-2 0x1p3 ] "integer i" [ -7 +8 0 2147483647 -2147483648 ]
                  "bool b" [ true false ] "spectrum s" [ 400 0.5 700 0.5 ] "spectrum n" "metal-Cu-k"
                  "string e" "" "string esc" "a\tb"
    )");
    const ParamSet& ps = d.shapes[0].params;
    EXPECT_EQ(ps.getFloats("a"), (std::vector<float>{1, -2.5f, 3, 0.5f, 100, -0.01f, 8}));
    EXPECT_EQ(ps.getInts("i"), (std::vector<int>{-7, 8, 0, 2147483647, -2147483647 - 1}));
    EXPECT_EQ(ps.find("b")->bools, (std::vector<bool>{true, false}));
    EXPECT_EQ(ps.getString("e", "x"), "");
    EXPECT_EQ(ps.getString("esc", ""), "a\tb");
    EXPECT_EQ(ps.find("n")->strings.size(), 1u);
    EXPECT_EQ(ps.find("a")->loc.line, 2);
}

TEST(Parser, UnusedParametersWarn) {
    SceneDescription d = parse("Film \"rgb\" \"float nonsense\" 3 \"integer xresolution\" 10\nWorldBegin");
    int before = warningCount();
    d.film.params.getInt("xresolution", 1);
    d.film.params.reportUnused("Film \"rgb\" (parser test)");
    EXPECT_EQ(warningCount(), before + 1);
    d.film.params.reportUnused("Film \"rgb\" (parser test)");
    EXPECT_EQ(warningCount(), before + 1);
}

TEST(Parser, UnmatchedAttributeEndWarnsAndContinues) {
    // pbrt-v4 reports it and carries on.
    SceneDescription d = parse("WorldBegin\nAttributeEnd\nShape \"sphere\"\n");
    EXPECT_EQ(d.shapes.size(), 1u);
}

TEST(Parser, LargeInlineMeshParsesQuickly) {
    const int n = 300000;  // vertices
    std::string text = "WorldBegin\nShape \"trianglemesh\" \"point3 P\" [";
    text.reserve(size_t(n) * 30);
    auto add = [&](const std::string& v) {  // appends, avoiding GCC 12's false -Wrestrict on " " + s
        text += ' ';
        text += v;
    };
    for (int i = 0; i < n; ++i) {
        add(std::to_string(i * 0.25));
        add("1.5e-1 -3");
    }
    text += " ] \"integer indices\" [";
    for (int i = 0; i < n; ++i) add(std::to_string(i));
    text += " ]\n";
    auto t0 = std::chrono::steady_clock::now();
    SceneDescription d = parse(text);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    auto P = d.shapes.at(0).params.getPoint3s("P");
    ASSERT_EQ(P.size(), size_t(n));
    EXPECT_FLOAT_EQ(P[n - 1].x, float((n - 1) * 0.25));
    EXPECT_FLOAT_EQ(P[7].y, 0.15f);
    EXPECT_EQ(d.shapes[0].params.getInts("indices").size(), size_t(n));
    EXPECT_LT(seconds, 5.0) << "parsing " << text.size() << " bytes took " << seconds << " s";
}

TEST(Parser, DeepNestingIsBounded) {
    std::string text = "WorldBegin\nAttribute \"shape\" \"float radius\" [ 1 2 3 4 5 6 7 8 ]\n";
    for (int i = 0; i < 100000; ++i) text += "AttributeBegin\n";
    text += "Shape \"sphere\"\n";
    for (int i = 0; i < 100000; ++i) text += "AttributeEnd\n";
    SceneDescription d = parse(text);
    EXPECT_EQ(d.shapes.size(), 1u);
}

// Mutated scenes either parse or fail with an InputError: never another exception or a crash.
TEST(Parser, MutatedInputOnlyGivesInputErrors) {
    const std::string base = R"(LookAt 0 0 5 0 0 0 0 1 0
Camera "perspective" "float fov" [ 45 ]
Film "rgb" "integer xresolution" [ 64 ] "string filename" "a.exr"
WorldBegin
Attribute "shape" "float radius" 2
AttributeBegin
  Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]
  AreaLightSource "diffuse" "blackbody L" 5000
  Translate 1 2 3
  Shape "trianglemesh" "point3 P" [ 0 0 0 1 0 0 0 1 0 ] "integer indices" [ 0 1 2 ]
AttributeEnd
ObjectBegin "o"
  Shape "sphere"
ObjectEnd
ObjectInstance "o"
Texture "t" "spectrum" "checkerboard" "spectrum tex1" [ 400 1 700 1 ]
MakeNamedMaterial "m" "string type" "conductor" "spectrum eta" "metal-Cu-eta"
NamedMaterial "m"
Transform [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 ]
Shape "sphere" "bool b" true
)";
    const char* inserts[] = {"[", "]", "\"", "\\", "#", "\n", " ", "AttributeBegin", "AttributeEnd", "ObjectBegin \"o\"",
                             "ObjectEnd", "WorldBegin", "inf", "-nan", "1e99", "0x", "\"float x\"", "Include \"x\"", "Import \"y\""};
    std::mt19937 rng(12345);
    int accepted = 0, rejected = 0;
    setWarningsQuiet(true);
    for (int iter = 0; iter < 3000; ++iter) {
        std::string s = base;
        int edits = 1 + int(rng() % 4);
        for (int e = 0; e < edits && !s.empty(); ++e) {
            size_t pos = rng() % s.size();
            switch (rng() % 4) {
                case 0: s.erase(pos, 1 + rng() % 12); break;
                case 1: s.insert(pos, inserts[rng() % std::size(inserts)]); break;
                case 2: s[pos] = char(rng() % 256); break;
                case 3: s.resize(pos); break;
            }
        }
        try {
            parseSceneString(s, ".", "fuzz.pbrt");
            ++accepted;
        } catch (const InputError&) {
            ++rejected;
        }
    }
    EXPECT_GT(rejected, 0);
    EXPECT_GT(accepted, 0);
}

// The shared pbrt-v4 scenes parse, with the expected numbers of shapes and lights.
TEST(Parser, SharedScenes) {
    const fs::path root = fs::path(PATHSPACE_SHARED_DIR) / "scenes";
    REQUIRE_SHARED_DATA(root);
    struct Expect {
        const char* file;
        size_t shapes, lights, areaLights, emissiveShapes;
    };
    const Expect scenes[] = {
        {"cornell-box/scene-v4.pbrt", 8, 0, 1, 1},
        {"veach-mis/scene-v4.pbrt", 9, 0, 3, 3},
        {"veach-bidir/scene-v4.pbrt", 14, 0, 2, 2},
        {"veach-ajar/scene-v4.pbrt", 22, 0, 1, 1},
        {"water-caustic/scene-v4.pbrt", 10, 0, 1, 1},
        {"caustic-glass/caustic-glass-v4.pbrt", 2, 1, 0, 0},
        {"veach-mis-classic/scene-v4.pbrt", 10, 0, 5, 5},
        {"cornell-box-measured/scene-v4.pbrt", 8, 0, 1, 1},
    };
    for (const Expect& e : scenes) {
        fs::path f = root / e.file;
        if (!fs::exists(f)) {
            ADD_FAILURE() << f << " is missing";
            continue;
        }
        SceneDescription d;
        ASSERT_NO_THROW(d = parseSceneFile(f.string())) << e.file << ": " << fileErrorOf(f);
        size_t emissive = 0;
        for (const ShapeEntity& s : d.shapes) emissive += s.areaLight >= 0;
        EXPECT_EQ(d.shapes.size(), e.shapes) << e.file;
        EXPECT_EQ(d.lights.size(), e.lights) << e.file;
        EXPECT_EQ(d.areaLights.size(), e.areaLights) << e.file;
        EXPECT_EQ(emissive, e.emissiveShapes) << e.file;
        EXPECT_TRUE(d.cameraGiven) << e.file;
        EXPECT_EQ(d.baseDirectory, f.parent_path().string()) << e.file;
    }
}

// pbrt-v3 files in the shared scenes are refused with a message that says so.
TEST(Parser, SharedPbrtV3SceneIsRefusedClearly) {
    fs::path f = fs::path(PATHSPACE_SHARED_DIR) / "scenes/caustic-glass/glass.pbrt";
    REQUIRE_SHARED_DATA(f);
    std::string e = fileErrorOf(f);
    EXPECT_NE(e.find("pbrt-v3"), std::string::npos) << e;
    EXPECT_NE(e.find("glass.pbrt:"), std::string::npos) << e;
}
