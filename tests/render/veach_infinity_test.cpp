// Veach's path-space MLT with lights at infinity (path_space.h: a light vertex that is a
// direction, in the solid-angle measure): images against BDPT's (agreement.h: block and
// image means within 4 sigma, sigma measured across independent renders) on small scenes
// lit by a constant infinite light, an image infinite light and a distant light, each with a
// diffuse floor and an occluder; the sky seen in a mirror (a lens perturbation retracing a
// chain E S to infinity) and a distant light's caustic through glass (L S S D E: caustic
// perturbations from a direction) put specular chains ending at the light under the
// perturbations, each also alone beside the bidirectional mutation.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <string>

#include "agreement.h"
#include "mlt_scenes.h"
#include "mutation_cases.h"
#include "render_helpers.h"
#include "temp_images.h"

using namespace ps;
using namespace ps::test;

namespace {

// A floor, a diffuse sphere and a roof casting a shadow on it, under `light`; `extra` adds
// shapes.
std::string litFromInfinity(const std::string& light, const std::string& extra = "", int bootstrap = 100000) {
    return std::string(R"(
        LookAt 0 1.8 2.4  0 0.2 0  0 1 0
        Camera "perspective" "float fov" [ 45 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        )") + mltIntegrator(bootstrap) + R"(
        WorldBegin
        )" + light + R"(
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -1.2 0 1.2   1.2 0 1.2   -1.2 0 -1.2   1.2 0 -1.2 ]
        Material "diffuse" "rgb reflectance" [ 0.6 0.3 0.2 ]
        Shape "bilinearmesh" "point3 P" [ -0.8 0.7 -0.2   0 0.7 -0.2   -0.8 0.7 0.5   0 0.7 0.5 ]
        AttributeBegin
          Material "diffuse" "rgb reflectance" [ 0.3 0.4 0.7 ]
          Translate 0.5 0.25 0.1
          Shape "sphere" "float radius" [ 0.25 ]
        AttributeEnd
        )" + extra;
}

// A mirror standing behind the floor: the sky, the floor and the sphere seen in it.
const char* kMirror = R"(
        AttributeBegin
          Material "conductor" "rgb reflectance" [ 0.9 0.9 0.9 ] "float roughness" [ 0 ]
          Shape "bilinearmesh" "point3 P" [ -1 0 -1.1   1 0 -1.1   -1 1.2 -1.3   1 1.2 -1.3 ]
        AttributeEnd
)";

// A glass sphere over the floor: a distant light's caustic under it, seen directly.
const char* kGlass = R"(
        AttributeBegin
          Material "dielectric" "float eta" [ 1.5 ]
          Translate 0.2 0.6 0.7
          Shape "sphere" "float radius" [ 0.2 ]
        AttributeEnd
)";

std::string constantSkyWithMirror() {
    return litFromInfinity(R"(LightSource "infinite" "rgb L" [ 0.6 0.7 0.9 ])", kMirror);
}

std::string distantLightThroughGlass() {
    return litFromInfinity(R"(LightSource "distant" "point3 from" [ 0.3 1 0.4 ] "point3 to" [ 0 0 0 ] "rgb L" [ 3 3 3 ])",
                           kGlass, 150000);
}

// An equal-area map, dim but for a bright spot of four texels near the zenith (+z of the
// map turned to +y) and one low texel: sharp shadows beside the sky's soft ones.
std::string imageSky(const TempImages& tmp) {
    Image map(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const bool spot = (x == 3 || x == 4) && (y == 2 || y == 3);
            map.set(x, y, spot ? Spectrum(40.0f, 36.0f, 30.0f) : (x == 0 && y == 5) ? Spectrum(20.0f, 8.0f, 4.0f) : Spectrum(0.2f, 0.25f, 0.35f));
        }
    return litFromInfinity("AttributeBegin\nRotate -90 1 0 0\nLightSource \"infinite\" \"string filename\" [ \"" +
                           tmp.write("veach-sky.pfm", map) + "\" ]\nAttributeEnd");
}

}  // namespace

TEST(VeachMLTInfinity, AgreesWithBDPTUnderAConstantSkyWithAMirror) {
    expectAgreement(AgreementCase{"constant sky, mirror", constantSkyWithMirror(), {"bdpt", "mlt"}, 16, 16, {{"mlt", 64}}, 0.02});
}

TEST(VeachMLTInfinity, AgreesWithBDPTUnderAnImageSky) {
    TempImages tmp("veach-image-sky");
    expectAgreement(AgreementCase{"image sky", imageSky(tmp), {"bdpt", "mlt"}, 16, 16, {{"mlt", 64}}, 0.02});
}

TEST(VeachMLTInfinity, AgreesWithBDPTUnderADistantLightThroughGlass) {
    expectAgreement(AgreementCase{"distant light, glass", distantLightThroughGlass(), {"bdpt", "mlt"}, 64, 16, {{"mlt", 128}}, 0.02});
}

class VeachMLTInfinityMutation : public ::testing::TestWithParam<MutationCase> {};

// Each perturbation alone beside the bidirectional mutation, on chains that end at the light
// at infinity: the image against BDPT's, and the perturbation proposed and accepted, but not
// always.
TEST_P(VeachMLTInfinityMutation, WithTheBidirectionalOneAgreesWithBDPT) { expectMutationAgreesAndApplies(GetParam()); }

INSTANTIATE_TEST_SUITE_P(
    Mutations, VeachMLTInfinityMutation,
    ::testing::Values(
        MutationCase{"lens perturbation, sky in a mirror", "lens-subpath=0,lens=1,multi-chain=0,caustic=0",
                             constantSkyWithMirror, 16, 64, "lens perturbation"},
        MutationCase{"lens subpath, sky in a mirror", "lens-subpath=1,lens=0,multi-chain=0,caustic=0",
                             constantSkyWithMirror, 16, 64, "lens subpath"},
        MutationCase{"caustic perturbation, distant light through glass", "lens-subpath=0,lens=0,multi-chain=0,caustic=1",
                             distantLightThroughGlass, 64, 128, "caustic perturbation"}),
    [](const ::testing::TestParamInfo<MutationCase>& i) {
        std::string n;
        for (const char* p = i.param.name; *p; ++p) n += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
        return n;
    });
