#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <fstream>

#include "scene/parser.h"
#include "scene/spectra.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

// The parameters of one Shape statement, parsed for real.
ParamSet shapeParams(const std::string& params, const std::string& base = ".") {
    setWarningsQuiet(true);
    SceneDescription d = parseSceneString("WorldBegin\nShape \"test\" " + params + "\n", base, "p.pbrt");
    return d.shapes.at(0).params;
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

Param numeric(ParamType type, const std::string& typeName, const std::string& name, std::vector<double> v) {
    Param p;
    p.type = type;
    p.typeName = typeName;
    p.name = name;
    p.numbers = std::move(v);
    p.loc = SourceLoc{"q.pbrt", 4, 2};
    return p;
}

}  // namespace

TEST(ParamSet, SingleValuesAndDefaults) {
    ParamSet ps = shapeParams(R"("float radius" 2.5 "integer n" [ -3 ] "bool on" true "string s" "x y"
                                 "point3 p" [ 1 2 3 ] "vector3 v" [ 0 0 1 ])");
    EXPECT_FLOAT_EQ(ps.getFloat("radius", 1), 2.5f);
    EXPECT_EQ(ps.getInt("n", 0), -3);
    EXPECT_TRUE(ps.getBool("on", false));
    EXPECT_EQ(ps.getString("s", ""), "x y");
    EXPECT_EQ(ps.getPoint3("p", {}).y, 2.0f);
    EXPECT_EQ(ps.getVector3("v", {}).z, 1.0f);
    EXPECT_FLOAT_EQ(ps.getFloat("absent", 7), 7.0f);
    EXPECT_EQ(ps.getString("absent", "def"), "def");
    EXPECT_TRUE(ps.has("radius"));
    EXPECT_FALSE(ps.has("absent"));
}

TEST(ParamSet, ArraysAndMultiples) {
    ParamSet ps = shapeParams(R"("point3 P" [ 0 0 0 1 0 0 0 1 0 ] "integer indices" [ 0 1 2 ] "point2 uv" [ 0 0 1 0 1 1 ]
                                 "normal N" [ 0 0 1 0 0 1 0 0 1 ] "vector3 S" [ 1 0 0 1 0 0 1 0 0 ] "float f" [ 1 2 ]
                                 "string names" [ "a" "b" ] "point3 bad" [ 1 2 ])");
    EXPECT_EQ(ps.getPoint3s("P").size(), 3u);
    EXPECT_EQ(ps.getInts("indices"), (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(ps.getPoint2s("uv").size(), 3u);
    EXPECT_EQ(ps.getNormals("N").size(), 3u);
    EXPECT_EQ(ps.getVector3s("S").size(), 3u);
    EXPECT_EQ(ps.getFloats("f"), (std::vector<float>{1, 2}));
    EXPECT_EQ(ps.getStrings("names"), (std::vector<std::string>{"a", "b"}));
    EXPECT_TRUE(ps.getFloats("absent").empty());
    std::string e = errorOf([&] { ps.getPoint3s("bad"); });
    EXPECT_NE(e.find("p.pbrt:4:"), std::string::npos) << e;
    EXPECT_NE(e.find("point3 bad"), std::string::npos) << e;
}

// pbrt-v4: the lookup must match the type exactly; a mismatch leaves the parameter unused.
TEST(ParamSet, WrongTypeIsIgnoredAndReportedUnused) {
    ParamSet ps = shapeParams(R"("float n" 3 "integer radius" 2)");
    EXPECT_EQ(ps.getInt("n", 11), 11);
    EXPECT_FLOAT_EQ(ps.getFloat("radius", 1.5f), 1.5f);
    int before = warningCount();
    ps.reportUnused("Shape \"test\"");
    EXPECT_EQ(warningCount(), before + 2);
}

TEST(ParamSet, WrongCountIsAnErrorAtTheParameter) {
    ParamSet ps = shapeParams("\n  \"float radius\" [ 1 2 ] \"point3 from\" [ 1 2 ]");
    std::string e = errorOf([&] { ps.getFloat("radius", 1); });
    EXPECT_NE(e.find("p.pbrt:3:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("float radius"), std::string::npos) << e;
    e = errorOf([&] { ps.getPoint3("from", {}); });
    EXPECT_NE(e.find("point3 from"), std::string::npos) << e;
}

TEST(ParamSet, LastOccurrenceWinsAndDefaultsDoNotOverride) {
    ParamSet ps = shapeParams(R"("float radius" 1 "float radius" 4)");
    EXPECT_EQ(ps.params.size(), 1u);
    EXPECT_FLOAT_EQ(ps.getFloat("radius", 0), 4.0f);
    Param def = numeric(ParamType::Float, "float", "radius", {9});
    def.fromAttribute = true;
    ps.addDefault(def);
    EXPECT_FLOAT_EQ(ps.getFloat("radius", 0), 4.0f);
    Param other = numeric(ParamType::Float, "float", "zmax", {0.5});
    other.fromAttribute = true;
    ps.addDefault(other);
    EXPECT_FLOAT_EQ(ps.getFloat("zmax", 0), 0.5f);
}

TEST(ParamSet, ReportUnusedWarnsOncePerParameterAndSkipsAttributes) {
    ParamSet ps = shapeParams(R"("float radius" 1 "float typo" 2 "string other" "x")");
    Param attr = numeric(ParamType::Float, "float", "fromattr", {1});
    attr.fromAttribute = true;
    ps.addDefault(attr);
    ps.getFloat("radius", 1);
    int before = warningCount();
    ps.reportUnused("Shape \"test\" (unique context 1)");
    EXPECT_EQ(warningCount(), before + 2);  // typo and other; not radius, not the attribute
    ps.reportUnused("Shape \"test\" (unique context 1)");
    EXPECT_EQ(warningCount(), before + 2);
}

TEST(ParamSet, RgbSpectraByKind) {
    ParamSet ps = shapeParams(R"("rgb a" [ 0.2 0.4 0.6 ] "rgb big" [ 2 3 4 ] "rgb neg" [ -1 0 0 ] "rgb two" [ 1 2 ])");
    Spectrum a = *ps.getSpectrum("a", SpectrumKind::Albedo);
    EXPECT_FLOAT_EQ(a.g, 0.4f);
    // pbrt-v4 refuses an RGB albedo above 1; emission keeps its magnitude.
    std::string e = errorOf([&] { ps.getSpectrum("big", SpectrumKind::Albedo); });
    EXPECT_NE(e.find("p.pbrt:2:"), std::string::npos) << e;
    EXPECT_NE(e.find("rgb big"), std::string::npos) << e;
    EXPECT_FLOAT_EQ(ps.getSpectrum("big", SpectrumKind::Illuminant)->b, 4.0f);
    EXPECT_FLOAT_EQ(ps.getSpectrum("big", SpectrumKind::Unbounded)->r, 2.0f);
    EXPECT_THROW(ps.getSpectrum("neg", SpectrumKind::Illuminant), InputError);
    EXPECT_THROW(ps.getSpectrum("two", SpectrumKind::Unbounded), InputError);
    EXPECT_FALSE(ps.getSpectrum("absent", SpectrumKind::Albedo).has_value());
}

TEST(ParamSet, SpectrumAndBlackbodyParameters) {
    ParamSet ps = shapeParams(R"("spectrum flat" [ 300 0.5 800 0.5 ] "spectrum cu" "metal-Cu-eta" "blackbody bb" 6500
                                 "spectrum down" [ 500 1 400 1 ] "spectrum odd" [ 400 1 500 ] "float notspectrum" 1
                                 "spectrum nothing" "no-such-spectrum")");
    Spectrum flat = *ps.getSpectrum("flat", SpectrumKind::Albedo);
    EXPECT_NEAR(flat.r, 0.5f, 1e-3);
    EXPECT_NEAR(flat.b, 0.5f, 1e-3);
    // A named spectrum as a parameter is the named spectrum (whose values spectra_test checks).
    Spectrum cu = *ps.getSpectrum("cu", SpectrumKind::Unbounded), named = *namedSpectrumToRGB("metal-Cu-eta", SpectrumKind::Unbounded);
    EXPECT_EQ(cu.r, named.r);
    EXPECT_EQ(cu.g, named.g);
    EXPECT_EQ(cu.b, named.b);
    EXPECT_NEAR(ps.getSpectrum("bb", SpectrumKind::Illuminant)->luminance(), 1.0f, 0.02);
    EXPECT_THROW(ps.getSpectrum("down", SpectrumKind::Albedo), InputError);
    EXPECT_THROW(ps.getSpectrum("odd", SpectrumKind::Albedo), InputError);
    EXPECT_FALSE(ps.getSpectrum("notspectrum", SpectrumKind::Albedo).has_value());  // wrong type: unused
    std::string e = errorOf([&] { ps.getSpectrum("nothing", SpectrumKind::Illuminant); });
    EXPECT_NE(e.find("no-such-spectrum"), std::string::npos) << e;
    EXPECT_NE(e.find("p.pbrt:4:"), std::string::npos) << e;

    // The pbrt-v3 [kelvin scale] form is refused, naming it.
    ParamSet v3;
    v3.add(numeric(ParamType::Blackbody, "blackbody", "L", {5500, 125}));
    e = errorOf([&] { v3.getSpectrum("L", SpectrumKind::Illuminant); });
    EXPECT_NE(e.find("pbrt-v3"), std::string::npos) << e;
    EXPECT_NE(e.find("q.pbrt:4:2"), std::string::npos) << e;
}

TEST(ParamSet, SpectrumFilesResolveAgainstTheBaseDirectory) {
    fs::path dir = fs::temp_directory_path() / ("pathspace-params-" + std::to_string(getpid()));
    fs::create_directories(dir / "spds");
    std::ofstream(dir / "spds" / "flat.spd") << "# wavelength value\n300 0.25\n550 0.25 # mid\n800 0.25\n";
    std::ofstream(dir / "spds" / "bad.spd") << "300 0.25 550\n";
    ParamSet ps = shapeParams(R"("spectrum s" "spds/flat.spd" "spectrum b" "spds/bad.spd")", dir.string());
    Spectrum s = *ps.getSpectrum("s", SpectrumKind::Albedo);
    EXPECT_NEAR(s.g, 0.25f, 1e-3);
    EXPECT_THROW(ps.getSpectrum("b", SpectrumKind::Albedo), InputError);
    fs::remove_all(dir);
}

// Only an index that changes with wavelength would make pbrt-v4 disperse light, so only
// that earns the "dispersion is not modelled" warning (materials/create.cpp).
TEST(ParamSet, SpectrallyVaryingValues) {
    fs::path dir = fs::temp_directory_path() / ("pathspace-params-var-" + std::to_string(getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "flat.spd") << "300 1.5\n900 1.5\n";
    std::ofstream(dir / "ramp.spd") << "300 1.5\n900 1.6\n";
    ParamSet ps = shapeParams(R"("rgb grey" [ 1.5 1.5 1.5 ] "rgb tinted" [ 1.5 1.5 1.6 ] "float f" 1.5
                                 "spectrum flat" [ 300 1.5 900 1.5 ] "spectrum ramp" [ 300 1.5 900 1.6 ]
                                 "spectrum narrow" [ 500 1.5 600 1.5 ] "spectrum glass" "glass-BK7"
                                 "spectrum flatfile" "flat.spd" "spectrum rampfile" "ramp.spd" "blackbody bb" 5000)",
                              dir.string());
    for (const char* constant : {"grey", "f", "flat", "flatfile", "absent"}) EXPECT_FALSE(ps.spectrallyVarying(constant)) << constant;
    // "narrow" is zero outside [500, 600] nm; BK7 follows its Sellmeier curve in pbrt-v4.
    for (const char* varying : {"tinted", "ramp", "narrow", "glass", "rampfile", "bb"}) EXPECT_TRUE(ps.spectrallyVarying(varying)) << varying;
    fs::remove_all(dir);
}

TEST(ParamSet, TexturesAreTheirOwnType) {
    ParamSet ps = shapeParams(R"("texture reflectance" "checks" "string name" "x")");
    EXPECT_EQ(ps.getTexture("reflectance"), "checks");
    EXPECT_EQ(ps.getTexture("name"), "");
    EXPECT_FALSE(ps.getSpectrum("reflectance", SpectrumKind::Albedo).has_value());
}
