// Agreement of independent estimators (thesis ch. 10's strongest check): path tracing,
// light tracing and BDPT estimate the same image (see agreement.h for the tests).
// Light tracing cannot see specular surfaces or the environment directly (no camera
// connection through a delta lobe), so scenes showing those compare path tracing and BDPT.
// The cases of one box run in both colour modes (--color rgb and spectral).
#include <gtest/gtest.h>

#include "agreement.h"

using namespace ps;
using namespace ps::test;

namespace {

// A 1 x 1 x 1 box open towards the camera, with coloured side walls, a ceiling light and
// whatever `contents` adds; `light` replaces the ceiling light when given.
std::string box(const std::string& contents, const std::string& integratorDepth = "5", const std::string& light = "") {
    std::string ceilingLight = light.empty() ? R"(
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 6 6 6 ]
          Shape "bilinearmesh" "point3 P" [ -0.2 0.99 -0.2   0.2 0.99 -0.2   -0.2 0.99 0.2   0.2 0.99 0.2 ]
        AttributeEnd)"
                                             : light;
    return R"(
        LookAt 0 0.5 2.2  0 0.5 0  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ )" +
           integratorDepth + R"( ]
        WorldBegin)" + ceilingLight + R"(
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 0 -0.5   0.5 0 -0.5 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 1 -0.5   0.5 1 -0.5   -0.5 1 0.5   0.5 1 0.5 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ]
        Material "diffuse" "rgb reflectance" [ 0.7 0.1 0.1 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   -0.5 0 -0.5   -0.5 1 0.5   -0.5 1 -0.5 ]
        Material "diffuse" "rgb reflectance" [ 0.1 0.7 0.1 ]
        Shape "bilinearmesh" "point3 P" [ 0.5 0 -0.5   0.5 0 0.5   0.5 1 -0.5   0.5 1 0.5 ]
    )" + contents;
}

// A glass sphere (index `eta`, a parameter list) under an area light, out of view above the
// frame; its caustic on the floor is in it.
std::string glassSphereCaustic(const std::string& eta) {
    return R"(
        LookAt 0 0.25 2  0 0 0  0 1 0
        Camera "perspective" "float fov" [ 20 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 6 ]
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
          Shape "bilinearmesh" "point3 P" [ -0.4 3 -0.4   0.4 3 -0.4   -0.4 3 0.4   0.4 3 0.4 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]
        Shape "bilinearmesh" "point3 P" [ -3 0 3   3 0 3   -3 0 -3   3 0 -3 ]
        AttributeBegin
          Material "dielectric" )" + eta + R"(
          Translate 0 1.1 0
          Shape "sphere" "float radius" [ 0.5 ]
        AttributeEnd
    )";
}

// The case in RGB mode, then in spectral mode (R, G, B compared too: agreement.h) with twice
// the samples (each sample's colour varies with its wavelengths).
void expectAgreementInBothModes(AgreementCase c) {
    c.spectral = false;
    expectAgreement(c);
    const std::string name = std::string("spectral ") + c.name;
    c.name = name.c_str();
    c.spectral = true;
    c.spp *= 2;
    for (auto& [integrator, spp] : c.sppOf) spp *= 2;
    expectAgreement(c);
}

}  // namespace

TEST(EstimatorAgreement, DiffuseBox) {
    expectAgreementInBothModes(AgreementCase{"diffuse box", box(R"(
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ]
        Shape "sphere" "float radius" [ 0.2 ]
    )"), {"path", "light", "bdpt"}, 16});
}

// The sphere itself is out of view (above the frame); its caustic on the floor is in it.
TEST(EstimatorAgreement, GlassSphereCaustic) {
    const std::string scene = glassSphereCaustic(R"("float eta" [ 1.5 ])");
    expectAgreement(AgreementCase{"glass caustic", scene, {"bdpt", "light", "path"}, 384, 16, {{"light", 768}, {"path", 832}}});
}

// BDPT with a light subpath for a quarter of its camera samples (--light-paths 0.25), the
// others path tracing's. Unbiased where light subpaths add little (the box), where they carry
// the image (the caustic, which path tracing samples poorly), and where only they can (the
// caustic of a point light, which path tracing cannot sample: those paths count 4 times).
TEST(EstimatorAgreement, BdptWithFewerLightPaths) {
    expectAgreement(AgreementCase{"fewer light paths, box", box(R"(
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ]
        Shape "sphere" "float radius" [ 0.2 ]
    )"), {"path", "bdpt:light-paths=0.25"}, 16});
    expectAgreement(AgreementCase{"fewer light paths, caustic", glassSphereCaustic(R"("float eta" [ 1.5 ])"),
                                  {"bdpt", "bdpt:light-paths=0.25"}, 384, 16, {{"bdpt:light-paths=0.25", 768}}});
    std::string pointLit = glassSphereCaustic(R"("float eta" [ 1.5 ])");
    const std::string area = R"(AreaLightSource "diffuse" "rgb L" [ 8 8 8 ]
          Shape "bilinearmesh" "point3 P" [ -0.4 3 -0.4   0.4 3 -0.4   -0.4 3 0.4   0.4 3 0.4 ])";
    ASSERT_NE(pointLit.find(area), std::string::npos);
    pointLit.replace(pointLit.find(area), area.size(), R"(LightSource "point" "rgb I" [ 2 2 2 ] "point3 from" [ 0 3 0 ])");
    // 2%: the caustic is a large part of the image, and without the 1 / share its three
    // quarters would be missing.
    expectAgreement(AgreementCase{"fewer light paths, point-lit caustic", pointLit, {"bdpt", "bdpt:light-paths=0.25"},
                                  384, 16, {{"bdpt:light-paths=0.25", 768}}, 0.02});
}

TEST(EstimatorAgreement, GlossyConductor) {
    expectAgreementInBothModes(AgreementCase{"rough conductor", box(R"(
        Material "conductor" "spectrum eta" "metal-Cu-eta" "spectrum k" "metal-Cu-k" "float roughness" [ 0.25 ]
        Shape "sphere" "float radius" [ 0.3 ]
    )"), {"path", "light", "bdpt"}, 16});
}

// A smooth mirror shows the light: light tracing cannot connect through it.
TEST(EstimatorAgreement, AreaLightSeenInMirror) {
    expectAgreementInBothModes(AgreementCase{"mirror", box(R"(
        Material "conductor" "rgb reflectance" [ 0.9 0.9 0.9 ] "float roughness" [ 0 ]
        Shape "bilinearmesh" "point3 P" [ -0.45 0.01 0.3   0.45 0.01 0.3   -0.45 0.01 -0.45   0.45 0.01 -0.45 ]
    )"), {"path", "bdpt"}, 32});
}

// The environment is seen directly at the image's top: path tracing against BDPT; light
// tracing on the same scene seen from above (ground and object only).
TEST(EstimatorAgreement, EnvironmentLitObject) {
    auto scene = [](const char* lookAt) {
        return std::string(lookAt) + R"(
        Camera "perspective" "float fov" [ 40 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 4 ]
        WorldBegin
        LightSource "infinite" "rgb L" [ 0.6 0.7 0.9 ]
        Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
        Shape "bilinearmesh" "point3 P" [ -1.5 0 1.5   1.5 0 1.5   -1.5 0 -1.5   1.5 0 -1.5 ]
        Material "diffuse" "rgb reflectance" [ 0.8 0.4 0.2 ]
        Translate 0 0.4 0
        Shape "sphere" "float radius" [ 0.4 ]
    )";
    };
    expectAgreement(AgreementCase{"environment (side)", scene("LookAt 0 0.6 3  0 0.4 0  0 1 0"), {"path", "bdpt"}, 16});
    expectAgreement(AgreementCase{"environment (above)", scene("LookAt 0 3 0.01  0 0 0  0 1 0"), {"path", "light", "bdpt"}, 16, 16, {{"light", 224}}});
}

TEST(EstimatorAgreement, PointAndSpotLights) {
    std::string lights = R"(
        LightSource "point" "rgb I" [ 0.6 0.6 0.6 ] "point3 from" [ -0.2 0.8 0.1 ]
        LightSource "spot" "rgb I" [ 2 2 2 ] "point3 from" [ 0.3 0.9 0.3 ] "point3 to" [ 0 0 0 ]
            "float coneangle" [ 30 ] "float conedeltaangle" [ 10 ])";
    expectAgreementInBothModes(AgreementCase{"point and spot", box(R"(
        Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ]
        Shape "sphere" "float radius" [ 0.2 ]
    )", "5", lights), {"path", "light", "bdpt"}, 48, 16, {{"light", 80}}});
}

// Non-symmetric scattering (thesis ch. 5): a coarse octahedron with smooth vertex normals
// (shading normals far from the geometric ones) lit through a refractive slab. Light
// tracing needs the adjoint BSDF (the shading-normal factor, and no 1/eta^2 radiance
// scaling) to agree with path tracing here.
TEST(EstimatorAgreement, SmoothNormalsAndRefractiveSlab) {
    std::string scene = R"(
        LookAt 0 0.6 2.5  0 0.3 0  0 1 0
        Camera "perspective" "float fov" [ 25 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 5 ]
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 5 5 5 ]
          Shape "bilinearmesh" "point3 P" [ -0.8 3 -0.8   0.8 3 -0.8   -0.8 3 0.8   0.8 3 0.8 ]
        AttributeEnd
        AttributeBegin
          Material "dielectric" "float eta" [ 1.5 ]
          Shape "trianglemesh" "point3 P" [ -1.2 1.5 -1.2  1.2 1.5 -1.2  1.2 1.5 1.2  -1.2 1.5 1.2
                                            -1.2 1.7 -1.2  1.2 1.7 -1.2  1.2 1.7 1.2  -1.2 1.7 1.2 ]
              "integer indices" [ 0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -3 0 3   3 0 3   -3 0 -3   3 0 -3 ]
        Material "diffuse" "rgb reflectance" [ 0.8 0.5 0.3 ]
        Translate 0 0.36 0
        Shape "trianglemesh" "point3 P" [ 0.35 0 0  -0.35 0 0  0 0.35 0  0 -0.35 0  0 0 0.35  0 0 -0.35 ]
            "normal N" [ 1 0 0  -1 0 0  0 1 0  0 -1 0  0 0 1  0 0 -1 ]
            "integer indices" [ 0 2 4  2 1 4  1 3 4  3 0 4  2 0 5  1 2 5  3 1 5  0 3 5 ]
    )";
    expectAgreement(AgreementCase{"smooth normals, slab", scene, {"path", "light", "bdpt"}, 1024, 16, {{"light", 1536}, {"bdpt", 768}}});
}

// Spectral mode (--color spectral): the same agreements with every spectrum evaluated at
// each path's wavelengths, light tracing's and BDPT's splats converted through the sensor
// at the splat, and the image's R, G, B compared as well as its luminance.

// Saturated walls, a gold sphere (measured named spectra) and a blackbody ceiling light.
TEST(SpectralAgreement, SaturatedBoxUnderBlackbody) {
    const std::string light = R"(
        AttributeBegin
          AreaLightSource "diffuse" "blackbody L" [ 3200 ] "float scale" [ 6 ]
          Shape "bilinearmesh" "point3 P" [ -0.2 0.99 -0.2   0.2 0.99 -0.2   -0.2 0.99 0.2   0.2 0.99 0.2 ]
        AttributeEnd)";
    AgreementCase c{"spectral box", box(R"(
        Material "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" [ 0.3 ]
        Shape "sphere" "float radius" [ 0.25 ]
    )", "5", light), {"path", "light", "bdpt"}, 16};
    c.spectral = true;
    expectAgreement(c);
}

// Dispersion: the caustic of a flint-glass sphere (glass-F11), each refraction keeping only
// the first wavelength; light tracing and BDPT meet the dispersive vertex on the light
// subpath, the path tracer on the camera path.
TEST(SpectralAgreement, DispersiveGlassCaustic) {
    const std::string scene = glassSphereCaustic(R"("spectrum eta" "glass-F11")");
    // Each refraction keeps one wavelength, so colours vary more per sample than in RGB.
    AgreementCase c{"spectral dispersive caustic", scene, {"bdpt", "light", "path"}, 384, 16,
                    {{"light", 1024}, {"path", 1024}}, 0.015};
    c.spectral = true;
    expectAgreement(c);
}

// Lights whose emitted rays light tracing samples from their spectra (sampleLe): a coloured
// environment, a blackbody distant light and a spot light, seen from above.
TEST(SpectralAgreement, EnvironmentDistantAndSpotLights) {
    const std::string scene = R"(
        LookAt 0 3 0.01  0 0 0  0 1 0
        Camera "perspective" "float fov" [ 40 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 4 ]
        WorldBegin
        LightSource "infinite" "rgb L" [ 0.2 0.3 0.6 ]
        LightSource "distant" "blackbody L" [ 2500 ] "float scale" [ 1.5 ] "point3 from" [ 1 2 0.5 ] "point3 to" [ 0 0 0 ]
        LightSource "spot" "rgb I" [ 3 0.5 2 ] "point3 from" [ -0.5 1.5 0 ] "point3 to" [ 0 0 0 ]
            "float coneangle" [ 30 ] "float conedeltaangle" [ 10 ]
        Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
        Shape "bilinearmesh" "point3 P" [ -1.5 0 1.5   1.5 0 1.5   -1.5 0 -1.5   1.5 0 -1.5 ]
        Material "diffuse" "rgb reflectance" [ 0.1 0.7 0.2 ]
        Translate 0 0.4 0
        Shape "sphere" "float radius" [ 0.4 ]
    )";
    AgreementCase c{"spectral lights", scene, {"path", "light", "bdpt"}, 16, 16, {{"path", 48}, {"light", 224}, {"bdpt", 40}}};
    c.spectral = true;
    expectAgreement(c);
}
