// Light tracing and BDPT against path tracing (agreement.h) on the light setups the other
// agreement tests leave out: a distant light, a non-uniform environment map, two-sided
// emitters, a thin-lens camera, and refraction that light crosses only once (an emitter or
// the camera inside glass), where the radiance scaling by 1/eta^2 of the Radiance mode
// (thesis §5.2) does not cancel between entering and leaving the glass.
// Light tracing cannot image specular surfaces or the environment directly, so every view
// that light tracing renders shows only diffuse surfaces.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "agreement.h"
#include "image/image.h"
#include "mc/rng.h"
#include "temp_images.h"

using namespace ps;
using namespace ps::test;
namespace fs = std::filesystem;

namespace {

// The scene header shared by every case: a 24 x 24 box-filtered film.
std::string header(const std::string& lookAt, const std::string& camera, int maxDepth) {
    return lookAt + "\nCamera \"perspective\" " + camera + R"(
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ )" +
           std::to_string(maxDepth) + R"( ]
        WorldBegin
    )";
}

// A bilinear patch through four corners (u along a->b, v along a->c; normal (b-a) x (c-a)).
std::string quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    std::string s = "Shape \"bilinearmesh\" \"point3 P\" [";
    for (Vec3 p : {a, b, c, d})
        for (int i = 0; i < 3; ++i) {
            s += ' ';
            s += std::to_string(p[i]);
        }
    s += " ]\n";
    return s;
}

// An axis-aligned box's faces with outward normals (a dielectric tells its inside by the
// normal); without the bottom face when `open`.
std::string boxFaces(Vec3 lo, Vec3 hi, bool open = false) {
    float x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
    std::string s = quad({x0, y1, z1}, {x1, y1, z1}, {x0, y1, z0}, {x1, y1, z0});
    if (!open) s += quad({x0, y0, z0}, {x1, y0, z0}, {x0, y0, z1}, {x1, y0, z1});
    s += quad({x0, y0, z1}, {x1, y0, z1}, {x0, y1, z1}, {x1, y1, z1});
    s += quad({x1, y0, z0}, {x0, y0, z0}, {x1, y1, z0}, {x0, y1, z0});
    s += quad({x0, y0, z0}, {x0, y0, z1}, {x0, y1, z0}, {x0, y1, z1});
    s += quad({x1, y0, z1}, {x1, y0, z0}, {x1, y1, z1}, {x1, y1, z0});
    return s;
}

// A grey ground square of half-width s at y = 0 with an orange ball on it.
std::string groundAndBall(float s = 1.5f) {
    return R"(Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
        )" + quad({-s, 0, s}, {s, 0, s}, {-s, 0, -s}, {s, 0, -s}) + R"(
        AttributeBegin
          Material "diffuse" "rgb reflectance" [ 0.8 0.4 0.2 ]
          Translate 0.1 0.3 -0.1
          Shape "sphere" "float radius" [ 0.3 ]
        AttributeEnd
    )";
}

// A room 1 wide and deep and h high, open towards +z (the camera's side), with coloured
// side walls.
std::string room(float h = 1) {
    return R"(Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        )" + quad({-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f}, {-0.5f, 0, -0.5f}, {0.5f, 0, -0.5f}) +
           quad({-0.5f, h, -0.5f}, {0.5f, h, -0.5f}, {-0.5f, h, 0.5f}, {0.5f, h, 0.5f}) +
           quad({-0.5f, 0, -0.5f}, {0.5f, 0, -0.5f}, {-0.5f, h, -0.5f}, {0.5f, h, -0.5f}) + R"(
        Material "diffuse" "rgb reflectance" [ 0.7 0.1 0.1 ]
        )" + quad({-0.5f, 0, 0.5f}, {-0.5f, 0, -0.5f}, {-0.5f, h, 0.5f}, {-0.5f, h, -0.5f}) + R"(
        Material "diffuse" "rgb reflectance" [ 0.1 0.7 0.1 ]
        )" + quad({0.5f, 0, -0.5f}, {0.5f, 0, 0.5f}, {0.5f, h, -0.5f}, {0.5f, h, 0.5f});
}

// An equal-area environment map with a small sun a few hundred times brighter than a
// blue-to-brown sky gradient, in a temporary directory removed with the object.
struct TempEnvironmentMap {
    fs::path dir = fs::temp_directory_path() / ("pathspace-agree-env-" + std::to_string(getpid()));
    std::string file = (dir / "sky.pfm").string();
    TempEnvironmentMap() {
        fs::create_directories(dir);
        const int n = 32;
        Image img(n, n);
        Rng rng(4);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                float t = float(x + y) / (2 * n);
                Spectrum sky(0.3f + 0.5f * t, 0.35f + 0.3f * t, 0.6f - 0.4f * t);
                bool sun = x >= 20 && x < 22 && y >= 12 && y < 14;
                img.set(x, y, sun ? Spectrum(150, 140, 120) : sky * (0.8f + 0.4f * rng.uniform()));
            }
        writeImage(file, img);
    }
    ~TempEnvironmentMap() { fs::remove_all(dir); }
};

}  // namespace

// A distant light: light subpaths start on the disk at infinity with a delta direction
// (thesis §10.2), which path tracing reaches only by next-event estimation.
TEST(LightAgreement, DistantLight) {
    std::string scene = header("LookAt 0 2 2.2  0 0.2 0  0 1 0", R"("float fov" [ 40 ])", 4) + R"(
        LightSource "distant" "rgb L" [ 2.5 2.4 2.2 ] "point3 from" [ 1 3 1.5 ] "point3 to" [ 0 0 0 ]
    )" + groundAndBall();
    expectAgreement(AgreementCase{"distant", scene, {"path", "light", "bdpt"}, 32});
}

// A strongly non-uniform environment map (importance-sampled by luminance): seen directly
// from the side (path tracing and BDPT), and from above where only the ground and the ball
// show (light tracing too).
TEST(LightAgreement, NonUniformEnvironment) {
    TempEnvironmentMap env;
    std::string lights = R"(
        AttributeBegin
          Rotate -90 1 0 0
          LightSource "infinite" "string filename" [ ")" + env.file + R"(" ]
        AttributeEnd
    )";
    expectAgreement(AgreementCase{"environment (side)",
                                  header("LookAt 0 0.6 3  0 0.4 0  0 1 0", R"("float fov" [ 40 ])", 4) + lights +
                                      groundAndBall(),
                                  {"path", "bdpt"}, 16});
    expectAgreement(AgreementCase{"environment (above)",
                                  header("LookAt 0 3 0.01  0 0 0  0 1 0", R"("float fov" [ 40 ])", 4) + lights +
                                      groundAndBall(),
                                  {"path", "light", "bdpt"}, 64});
}

// Two-sided quad emitters standing on the ground: the left one's normal faces the camera,
// the right one's faces away, and each lights the ground and a ball on both of its sides.
TEST(LightAgreement, TwoSidedEmitters) {
    std::string scene = header("LookAt 0 1.6 2  0 0.2 0  0 1 0", R"("float fov" [ 45 ])", 4) + R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 3 3 3 ] "bool twosided" [ true ]
          Material "diffuse" "rgb reflectance" [ 0.2 0.2 0.2 ]
          Shape "bilinearmesh" "point3 P" [ -0.6 0.05 0   -0.1 0.05 0   -0.6 0.45 0   -0.1 0.45 0 ]
          Shape "bilinearmesh" "point3 P" [ 0.6 0.05 0.1   0.1 0.05 0.1   0.6 0.45 0.1   0.1 0.45 0.1 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
        Shape "bilinearmesh" "point3 P" [ -1.2 0 1.2   1.2 0 1.2   -1.2 0 -1.2   1.2 0 -1.2 ]
        Material "diffuse" "rgb reflectance" [ 0.3 0.5 0.8 ]
        AttributeBegin
          Translate -0.35 0.15 -0.45
          Shape "sphere" "float radius" [ 0.15 ]
        AttributeEnd
        AttributeBegin
          Translate 0.35 0.15 0.55
          Shape "sphere" "float radius" [ 0.15 ]
        AttributeEnd
    )";
    expectAgreement(AgreementCase{"two-sided emitters", scene, {"path", "light", "bdpt"}, 32});
}

// A thin lens (lensradius > 0) focused on the ball in the room's middle: the back wall and
// a nearer ball are out of focus. Light tracing and BDPT connect to points on the lens
// (importance W_e = 1 / (A_film A_lens cos^4), thesis §8.1.1).
TEST(LightAgreement, ThinLensCamera) {
    std::string scene = header("LookAt 0 0.5 2.2  0 0.5 0  0 1 0",
                               R"("float fov" [ 30 ] "float lensradius" [ 0.08 ] "float focaldistance" [ 2.2 ])", 4) +
                        R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 6 6 6 ]
          Shape "bilinearmesh" "point3 P" [ -0.2 0.99 -0.2   0.2 0.99 -0.2   -0.2 0.99 0.2   0.2 0.99 0.2 ]
        AttributeEnd
    )" + room() + R"(
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ]
        AttributeBegin
          Translate 0 0.2 0
          Shape "sphere" "float radius" [ 0.2 ]
        AttributeEnd
        AttributeBegin
          Translate 0.2 0.3 0.9
          Shape "sphere" "float radius" [ 0.08 ]
        AttributeEnd
    )";
    expectAgreement(AgreementCase{"thin lens", scene, {"path", "light", "bdpt"}, 48});
}

// (a) An emitter inside glass lights a low room: the ceiling is a closed glass slab with a
// quad emitter inside it. Every light path leaves the glass once, so radiance is scaled by
// 1/eta^2 once and nothing cancels it. The slab is above the frame (light tracing cannot
// image it).
TEST(LightAgreement, EmitterInsideGlass) {
    std::string scene = header("LookAt 0 0.25 1  0 0 -0.5  0 1 0", R"("float fov" [ 30 ])", 4) + room(0.5f) +
                        R"(
        AttributeBegin
          Material "dielectric" "float eta" [ 1.5 ]
          )" + boxFaces({-0.49f, 0.42f, -0.49f}, {0.49f, 0.49f, 0.49f}) + R"(
        AttributeEnd
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 2 2 2 ]
          )" + quad({-0.48f, 0.48f, -0.48f}, {0.48f, 0.48f, -0.48f}, {-0.48f, 0.48f, 0.48f}, {0.48f, 0.48f, 0.48f}) + R"(
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ]
        AttributeBegin
          Translate 0 0.12 0
          Shape "sphere" "float radius" [ 0.12 ]
        AttributeEnd
    )";
    // Spectral mode's wavelength noise needs a third more samples for light tracing's 1%.
    expectAgreement(AgreementCase{"emitter in glass", scene, {"path", "light", "bdpt"}, defaultSpectral() ? 224 : 160});
}

// (b) The camera inside a glass ball, looking down at diffuse objects inside it (a ground
// disk across the ball and a ball on it), lit by a quad light above: light enters the glass
// once and reaches the lens without leaving it. The view shows only the diffuse objects.
TEST(LightAgreement, CameraInsideGlass) {
    std::string scene = header("LookAt 0 0.4 0  0 0 0  0 0 -1", R"("float fov" [ 70 ])", 6) + R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 3 3 3 ]
          )" + quad({-0.7f, 0.65f, -0.7f}, {0.7f, 0.65f, -0.7f}, {-0.7f, 0.65f, 0.7f}, {0.7f, 0.65f, 0.7f}) + R"(
        AttributeEnd
        AttributeBegin
          Material "dielectric" "float eta" [ 1.5 ]
          Shape "sphere" "float radius" [ 0.6 ]
        AttributeEnd
        AttributeBegin
          Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
          Rotate -90 1 0 0
          Shape "disk" "float radius" [ 0.58 ]
        AttributeEnd
        AttributeBegin
          Material "diffuse" "rgb reflectance" [ 0.8 0.4 0.2 ]
          Translate 0.05 0.1 -0.1
          Shape "sphere" "float radius" [ 0.1 ]
        AttributeEnd
    )";
    expectAgreement(AgreementCase{"camera in glass", scene, {"path", "light", "bdpt"}, 128});
}

// (c) A diffuse floor closing an open-bottomed glass block, seen only from inside the glass
// (the camera is in it, looking down so that only the floor and a ball show), lit by a quad
// light just above the block: light refracts into the glass and never leaves it.
TEST(LightAgreement, DiffuseUnderGlassSeenFromInside) {
    std::string scene = header("LookAt 0 0.5 0  0 0 0  0 0 -1", R"("float fov" [ 70 ])", 6) + R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 3 3 3 ]
          )" + quad({-0.5f, 0.7f, -0.5f}, {0.5f, 0.7f, -0.5f}, {-0.5f, 0.7f, 0.5f}, {0.5f, 0.7f, 0.5f}) + R"(
        AttributeEnd
        AttributeBegin
          Material "dielectric" "float eta" [ 1.5 ]
          )" + boxFaces({-0.4f, 0, -0.4f}, {0.4f, 0.6f, 0.4f}, true) + R"(
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
        )" + quad({-0.4f, 0, 0.4f}, {0.4f, 0, 0.4f}, {-0.4f, 0, -0.4f}, {0.4f, 0, -0.4f}) + R"(
        Material "diffuse" "rgb reflectance" [ 0.8 0.4 0.2 ]
        AttributeBegin
          Translate 0.1 0.1 -0.1
          Shape "sphere" "float radius" [ 0.1 ]
        AttributeEnd
    )";
    expectAgreement(AgreementCase{"diffuse under glass", scene, {"path", "light", "bdpt"}, 96});
}

namespace {

// A w x h image of smoothly varying colours with a few bright texels.
Image patternImage(int w, int h, uint64_t seed) {
    Image img(w, h);
    Rng rng(seed);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float s = float(x) / w, t = float(y) / h;
            Spectrum c(0.2f + 0.8f * s, 0.3f + 0.6f * t, 0.9f - 0.6f * s * t);
            img.set(x, y, rng.uniform() < 0.1f ? c * 6 : c);
        }
    return img;
}

}  // namespace

// Lights defined by images (each a delta position or an emitter with varying radiance):
// a goniometric light (its image importance-sampled for light subpaths), a projection
// light aimed down at the ball (directions outside its frustum carry nothing), and a
// two-sided area light with an emission image, seen from above.
namespace {

// A goniometric light of intensity `intensity` (its parameter) and map `file`, tilted over
// the ground and ball.
std::string goniometricScene(const std::string& intensity, const std::string& file) {
    return header("LookAt 0 2 2.2  0 0.2 0  0 1 0", R"("float fov" [ 40 ])", 4) + R"(
        AttributeBegin
          Translate 0.3 1.6 0.4
          Rotate 150 1 0 0.3
          LightSource "goniometric" )" + intensity + R"( "string filename" [ ")" + file + R"(" ]
        AttributeEnd
    )" + groundAndBall();
}

// A projection light of slide `file` onto the ground and ball.
std::string projectionScene(const std::string& file) {
    return header("LookAt 0 2 2.2  0 0.2 0  0 1 0", R"("float fov" [ 40 ])", 4) + R"(
        AttributeBegin
          Translate 0 2 0.8
          Rotate 112 1 0 0
          LightSource "projection" "float fov" [ 40 ] "float scale" [ 4 ] "string filename" [ ")" + file + R"(" ]
        AttributeEnd
    )" + groundAndBall();
}

}  // namespace

TEST(LightAgreement, GoniometricLight) {
    TempImages tmp("agree-gonio");
    std::string file = tmp.write("gonio.pfm", patternImage(16, 16, 5));
    std::string scene = goniometricScene(R"("rgb I" [ 1.5 1.3 1.1 ])", file);
    expectAgreement(AgreementCase{"goniometric", scene, {"path", "light", "bdpt"}, 32, 16, {{"light", 128}}});
}

TEST(LightAgreement, ProjectionLight) {
    TempImages tmp("agree-projection");
    std::string file = tmp.write("slide.pfm", patternImage(8, 6, 6));
    std::string scene = projectionScene(file);
    expectAgreement(AgreementCase{"projection", scene, {"path", "light", "bdpt"}, 32});
}

// Spectral mode: the goniometric light's I (a blackbody here) and the projection light's
// slide (lifted as an illuminant per texel) at the path's wavelengths, in sampleLi, sampleLe
// and L alike.
TEST(LightAgreement, SpectralGoniometricLight) {
    TempImages tmp("agree-spectral-gonio");
    std::string file = tmp.write("gonio.pfm", patternImage(16, 16, 5));
    std::string scene = goniometricScene(R"("blackbody I" [ 3000 ] "float scale" [ 1.5 ])", file);
    AgreementCase c{"spectral goniometric", scene, {"path", "light", "bdpt"}, 32, 16, {{"light", 128}}};
    c.spectral = true;
    expectAgreement(c);
}

TEST(LightAgreement, SpectralProjectionLight) {
    TempImages tmp("agree-spectral-projection");
    std::string file = tmp.write("slide.pfm", patternImage(8, 6, 6));
    std::string scene = projectionScene(file);
    AgreementCase c{"spectral projection", scene, {"path", "light", "bdpt"}, 32};
    c.spectral = true;
    expectAgreement(c);
}

TEST(LightAgreement, ImageAreaLight) {
    TempImages tmp("agree-area-image");
    std::string file = tmp.write("emit.pfm", patternImage(8, 8, 7));
    std::string scene = header("LookAt 0 2 2.2  0 0.2 0  0 1 0", R"("float fov" [ 40 ])", 4) + R"(
        AttributeBegin
          AreaLightSource "diffuse" "string filename" [ ")" + file + R"(" ] "float scale" [ 1.5 ] "bool twosided" [ true ]
          Material "diffuse" "rgb reflectance" [ 0.2 0.2 0.2 ]
          )" + quad({-0.7f, 1.1f, -0.9f}, {0.5f, 1.1f, -0.9f}, {-0.7f, 1.3f, -0.1f}, {0.5f, 1.3f, -0.1f}) + R"(
        AttributeEnd
    )" + groundAndBall();
    expectAgreement(AgreementCase{"image area light", scene, {"path", "light", "bdpt"}, 48, 16, {{"light", 384}}});
}
