// The catalogue of bad inputs: each malformed scene, mesh or image file (or option) must give
// the documented exit status and a message that names the file (and line:column for scene
// text) and what is wrong, never a crash, a hang or raw binary bytes on the terminal.
// The test prints every case with the first line of its message: the catalogue itself.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include "run_binary.h"

namespace fs = std::filesystem;
using ps::test::Result;
using ps::test::runPathspace;

namespace {

const std::string kHeader = R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
Sampler "independent" "integer pixelsamples" [ 1 ]
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
)";

const std::string kPlyHeader =
    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

// kHeader with another Film line: `film` is its type and parameters.
std::string filmScene(const std::string& film) {
    std::string s = kHeader;
    size_t at = s.find("Film \"rgb\""), end = s.find('\n', at);
    return s.substr(0, at) + "Film " + film + " \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]" +
           s.substr(end) + "Shape \"sphere\"";
}

struct Case {
    std::string name;
    std::string scene;                                      // written as <name>.pbrt
    std::vector<std::pair<std::string, std::string>> files;  // extra files next to it
    int status;                                             // 2 = bad input, 0 = rendered with a warning
    std::vector<std::string> expect;                        // substrings of the output
    std::string options = "";
    std::vector<std::string> absent = {};                   // substrings the output must not have
};

std::vector<Case> cases() {
    std::string garbage(3000, '\0');
    std::mt19937 rng(7);
    for (char& c : garbage) c = char(rng() & 0xff);
    return {
        {"syntax_error", kHeader + "Shape \"sphere\" \"float radius\" [ 1 ", {}, 2, {":7:", "expected ']'"}},
        {"unterminated_string", kHeader + "Shape \"sphere", {}, 2, {":7:7:", "unterminated string"}},
        {"unknown_directive", kHeader + "Frobnicate 1 2 3", {}, 2, {":7:1:", "unknown directive"}},
        {"binary_garbage", garbage, {}, 2, {":1:"}},
        {"empty_file", "", {}, 2, {"before WorldBegin"}},
        {"huge_film", "Film \"rgb\" \"integer xresolution\" [ 1000000 ] \"integer yresolution\" [ 1000000 ]\nWorldBegin\n",
         {}, 2, {":1:1:", "1000000x1000000"}},
        {"negative_film", "Film \"rgb\" \"integer xresolution\" [ 0 ] \"integer yresolution\" [ -5 ]\nWorldBegin\n", {}, 2,
         {":1:1:", "0x-5"}},
        {"negative_index",
         kHeader + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 -1]", {}, 2,
         {":7:1:", "index -1 out of range"}},
        {"index_out_of_range",
         kHeader + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 7]", {}, 2,
         {":7:1:", "index 7 out of range"}},
        {"index_count_not_multiple_of_3",
         kHeader + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1]", {}, 0,
         {":7:1:", "not a multiple of 3"}},
        {"nan_in_transform", kHeader + "Translate nan 0 0\nShape \"sphere\"", {}, 2, {":7:11:", "finite"}},
        {"inf_in_transform", kHeader + "Translate 1e40 0 0\nShape \"sphere\"", {}, 2, {":7:11:", "out of single-precision range"}},
        {"inf_in_parameter", kHeader + "Shape \"sphere\" \"float radius\" [ 1e39 ]", {}, 2, {":7:", "range"}},
        {"nan_in_light", kHeader + "AreaLightSource \"diffuse\" \"rgb L\" [ -1 nan 1 ]\nShape \"sphere\"", {}, 2,
         {":7:", "finite"}},
        {"unknown_light_type", kHeader + "LightSource \"spotlight\" \"rgb I\" [ 1 1 1 ]\nShape \"sphere\"", {}, 2,
         {":7:1:", "unknown light type"}},
        // pbrt-v4 accepts a singular transform; a shape under it is the error, located there.
        {"singular_transform", kHeader + "Scale 0 0 0\nShape \"sphere\"", {}, 2,
         {":8:1: error: Shape:", "singular", "since Scale at ", ":7:1"}},
        {"singular_transform_without_shape",
         kHeader + "AttributeBegin\n  ConcatTransform [ 1 0 0 0  0 1 0 0  0 0 0 0  0 0 0 1 ]\nAttributeEnd\nShape \"sphere\"", {},
         0, {}, "", {"singular", "error"}},
        {"dispersion_warning", kHeader + "Material \"dielectric\" \"rgb eta\" [ 1.4 1.5 1.6 ]\nShape \"sphere\"", {}, 0,
         {":7:", "dispersion is modelled in spectral mode only"}, "--color rgb"},
        {"no_dispersion_warning_for_constant_eta",
         kHeader + "Material \"dielectric\" \"rgb eta\" [ 1.5 1.5 1.5 ]\nShape \"sphere\"\n"
                   "Material \"dielectric\" \"spectrum eta\" [ 300 1.33 900 1.33 ]\nShape \"sphere\"",
         {}, 0, {}, "", {"dispersion", "warning"}},
        // Spectral mode disperses, so it has nothing to warn about.
        {"no_dispersion_warning_in_spectral_mode",
         kHeader + "Material \"dielectric\" \"rgb eta\" [ 1.4 1.5 1.6 ]\nShape \"sphere\"", {}, 0, {}, "--color spectral",
         {"dispersion", "warning"}},
        {"whitebalance_warning_in_rgb_mode", filmScene("\"rgb\" \"float whitebalance\" [ 5000 ]"), {}, 0,
         {":3:1:", "whitebalance", "spectral mode only"}, "--color rgb"},
        {"no_whitebalance_warning_in_spectral_mode", filmScene("\"rgb\" \"float whitebalance\" [ 5000 ]"), {}, 0, {},
         "--color spectral", {"whitebalance", "warning"}},
        // pbrt-v4's gbuffer and spectral films: one warning each saying what is not written,
        // their own parameters read (not reported as unused).
        {"gbuffer_film", filmScene("\"gbuffer\" \"string coordinatesystem\" \"world\""), {}, 0,
         {":3:1:", "Film \"gbuffer\" is rendered as \"rgb\"", "geometric layers"}, "", {"unused", "coordinatesystem"}},
        {"spectral_film",
         filmScene("\"spectral\" \"integer nbuckets\" [ 8 ] \"float lambdamin\" [ 400 ] \"float lambdamax\" [ 700 ]"), {}, 0,
         {":3:1:", "Film \"spectral\" is rendered as \"rgb\"", "per-wavelength layers"}, "", {"unused", "nbuckets"}},
        {"unknown_film", filmScene("\"negative\""), {}, 0, {":3:1:", "\"negative\" is not a film type"}},
        {"degenerate_lookat",
         "LookAt 0 0 0  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\nShape \"sphere\"\n", {}, 2, {":1:1:", "LookAt"}},
        {"unknown_parameter", kHeader + "Shape \"sphere\" \"float radiuss\" [ 1 ]", {}, 0, {":7:", "radiuss"}},
        // subsurface (issue 36): located errors for what no medium can be, a warning for a typo.
        {"subsurface_unknown_name", kHeader + "Material \"subsurface\" \"string name\" \"Skin9\"\nShape \"sphere\"", {}, 2,
         {":7:23:", "no measured medium is named \"Skin9\"", "\"Skin1\""}},
        {"subsurface_eta_not_positive", kHeader + "Material \"subsurface\" \"float eta\" [ 0 ]\nShape \"sphere\"", {}, 2,
         {":7:23:", "\"eta\" must be positive"}},
        {"subsurface_unknown_parameter", kHeader + "Material \"subsurface\" \"float mfpp\" [ 1 ]\nShape \"sphere\"", {}, 0,
         {":7:", "mfpp"}},
        {"parameter_of_wrong_type", kHeader + "Shape \"sphere\" \"string radius\" [ \"big\" ]", {}, 0,
         {":7:", "string radius"}},
        {"binary_bytes_in_a_warning", kHeader + "Shape \"tri\x80\x01mesh\"", {}, 0, {":7:1:", "tri\\x80\\x01mesh"}},
        {"unsupported_shape", kHeader + "Shape \"paraboloid\" \"float radius\" [1]", {}, 0,
         {":7:1:", "not supported"}},
        {"loopsubdiv_inconsistent_winding",
         kHeader + "Shape \"loopsubdiv\" \"point3 P\" [0 0 0 1 0 0 0 1 0 0 0 1] \"integer indices\" [0 1 2 0 1 3]", {}, 2,
         {":7:1: error: loopsubdiv:", "same direction"}},
        {"loopsubdiv_too_many_levels",
         kHeader + "Shape \"loopsubdiv\" \"integer levels\" 40 \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]", {},
         2, {":7:1: error: loopsubdiv: 40 levels (1.21e+24 triangles) needs"}},
        {"unknown_named_spectrum", kHeader + "Material \"conductor\" \"spectrum eta\" \"metal-Unobtainium-eta\"\nShape \"sphere\"",
         {}, 2, {":7:", "metal-Unobtainium-eta"}},
        {"unmatched_attribute_end", kHeader + "AttributeEnd", {}, 0, {":7:1:", "AttributeEnd"}},
        {"undefined_object", kHeader + "ObjectInstance \"ghost\"", {}, 2, {":7:1:", "ghost"}},
        {"undefined_named_material", kHeader + "NamedMaterial \"ghost\"\nShape \"sphere\"", {}, 2,
         {":8:1:", "NamedMaterial \"ghost\" is not defined"}},
        {"missing_include", kHeader + "Include \"nothere.pbrt\"", {}, 2, {":7:1:", "nothere.pbrt"}},
        {"include_cycle", kHeader + "Include \"include_cycle.pbrt\"", {}, 2, {":7:1:", "cycle"}},
        // A file a directive names: the directive's place, then the file's own message.
        {"missing_ply", kHeader + "Shape \"plymesh\" \"string filename\" [ \"nothere.ply\" ]", {}, 2,
         {":7:1: error: ", "nothere.ply: cannot open"}},
        {"truncated_binary_ply", kHeader + "Shape \"plymesh\" \"string filename\" [ \"t.ply\" ]",
         {{"t.ply", kPlyHeader + std::string(4, '\0')}}, 2, {":7:1: error: ", "t.ply", "truncated"}},
        {"ply_index_out_of_range", kHeader + "Shape \"plymesh\" \"string filename\" [ \"o.ply\" ]",
         {{"o.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"}},
         2, {"o.ply", "index 9 out of range"}},
        {"ply_huge_count", kHeader + "Shape \"plymesh\" \"string filename\" [ \"h.ply\" ]",
         {{"h.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                    "property float y\nproperty float z\nend_header\n"}},
         2, {"h.ply", "4000000000"}},
        {"texture_not_an_image",
         kHeader + "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" [ \"fake.png\" ]\n"
                   "Material \"diffuse\" \"texture reflectance\" \"t\"\nShape \"sphere\"",
         {{"fake.png", "this is not a png\n"}}, 2, {":7:1: error: ", "fake.png", "not a readable image"}},
        {"missing_texture",
         kHeader + "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" [ \"none.png\" ]\n"
                   "Material \"diffuse\" \"texture reflectance\" \"t\"\nShape \"sphere\"",
         {}, 2, {":7:1: error: ", "none.png: cannot open image"}},
        {"missing_normal_map", kHeader + "Material \"diffuse\" \"string normalmap\" [ \"nm.png\" ]\nShape \"sphere\"",
         {}, 2, {":7:", "error: ", "nm.png: cannot open image"}},
        {"normal_map_not_an_image", kHeader + "Material \"diffuse\" \"string normalmap\" [ \"nm.png\" ]\nShape \"sphere\"",
         {{"nm.png", "this is not a png\n"}}, 2, {":7:", "error: ", "nm.png", "not a readable image"}},
        {"undefined_displacement_texture",
         kHeader + "Material \"diffuse\" \"texture displacement\" \"bumps\"\nShape \"sphere\"", {}, 2,
         {":7:", "error: ", "float texture \"bumps\" (for \"displacement\") is not defined"}},
        {"missing_environment_map", "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                                    "LightSource \"infinite\" \"string filename\" [ \"sky.exr\" ]\n",
         {}, 2, {":4:1: error: ", "sky.exr: cannot open image"}},
        {"bad_option_value", kHeader + "Shape \"sphere\"", {}, 2, {"--spp", "expected a whole number >= 1, got \"-3\""},
         "--spp -3"},
        {"unknown_integrator", kHeader + "Shape \"sphere\"", {}, 2, {"warp"}, "--integrator warp"},
        {"film_beyond_memory_limit", kHeader + "Shape \"sphere\"", {}, 2,
         {":3:1:", "Film 16x16 needs", "more than the limit of 1.0 KiB (raise it with --max-memory)"}, "--max-memory 1K"},
        {"bad_memory_size", kHeader + "Shape \"sphere\"", {}, 2, {"--max-memory", "got \"lots\""}, "--max-memory lots"},
    };
}

// Nothing but printable ASCII and line breaks reaches the terminal.
bool printable(const std::string& s) {
    for (unsigned char c : s)
        if ((c < 0x20 && c != '\n' && c != '\t') || c >= 0x7f) return false;
    return true;
}

}  // namespace

TEST(BadInputs, EachGivesItsStatusAndAClearMessage) {
    fs::path dir = fs::temp_directory_path() / ("pathspace-bad-inputs-" + std::to_string(getpid()));
    fs::create_directories(dir);
    for (const Case& c : cases()) {
        fs::path scene = dir / (c.name + ".pbrt");
        std::ofstream(scene, std::ios::binary) << c.scene;
        for (const auto& [name, text] : c.files) std::ofstream(dir / name, std::ios::binary) << text;
        Result r = runPathspace("render " + scene.string() + " --quiet --threads 1 -o " + (dir / "out.pfm").string() +
                                (c.options.empty() ? "" : " " + c.options));
        std::string first = r.out.substr(0, r.out.find('\n'));
        std::printf("  %-30s exit %d  %s\n", c.name.c_str(), r.status, first.c_str());
        EXPECT_EQ(r.status, c.status) << c.name << ": " << r.out;
        for (const std::string& e : c.expect) EXPECT_NE(r.out.find(e), std::string::npos) << c.name << ": " << r.out;
        for (const std::string& a : c.absent) EXPECT_EQ(r.out.find(a), std::string::npos) << c.name << ": " << r.out;
        EXPECT_TRUE(printable(r.out)) << c.name;
        EXPECT_EQ(r.out.find("Assertion"), std::string::npos) << c.name;
    }
    fs::remove_all(dir);
}
