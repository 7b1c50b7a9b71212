// The hair BSDF in the integrators: path tracing, light tracing and BDPT estimate the same
// image of a box holding a hair-material quad and sphere (see agreement.h). Light tracing
// and BDPT's light subpaths evaluate the BSDF in importance mode, the adjoint f(wi, wo) of
// this non-reciprocal model: with f(wo, wi) there they would converge to another image.
// On these shapes h = -1 + 2v is a property of the surface point, so the adjoint is exact.
// In spectral mode too: sigma_a lifted at the path's wavelengths (an unbounded RGB, and the
// melanin concentrations' RGB), and the lobe chosen by the mean over the four wavelengths.
#include <gtest/gtest.h>

#include "agreement.h"

using namespace ps;
using namespace ps::test;

namespace {

const std::string kScene = R"(
        LookAt 0 0.5 2.2  0 0.5 0  0 1 0
        Camera "perspective" "float fov" [ 30 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ 5 ]
        WorldBegin
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 6 6 6 ]
          Shape "bilinearmesh" "point3 P" [ -0.2 0.99 -0.2   0.2 0.99 -0.2   -0.2 0.99 0.2   0.2 0.99 0.2 ]
        AttributeEnd
        Material "diffuse" "rgb reflectance" [ 0.7 0.7 0.7 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 0.5   0.5 0 0.5   -0.5 0 -0.5   0.5 0 -0.5 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 1 -0.5   0.5 1 -0.5   -0.5 1 0.5   0.5 1 0.5 ]
        Shape "bilinearmesh" "point3 P" [ -0.5 0 -0.5   0.5 0 -0.5   -0.5 1 -0.5   0.5 1 -0.5 ]
        Material "hair" "rgb sigma_a" [ 0.2 0.6 1.5 ] "float beta_m" [ 0.35 ] "float beta_n" [ 0.4 ] "float alpha" [ 4 ]
        Shape "bilinearmesh" "point3 P" [ -0.4 0.05 0.1   0.1 0.05 -0.4   -0.4 0.8 0.1   0.1 0.8 -0.4 ]
        Material "hair" "float eumelanin" [ 0.3 ] "float beta_m" [ 0.5 ] "float beta_n" [ 0.6 ]
        AttributeBegin
          Translate 0.25 0.3 0.1
          Rotate 60 1 0 0
          Shape "sphere" "float radius" [ 0.22 ]
        AttributeEnd
    )";

}  // namespace

// 32 samples (light tracing 128): at 16 the hair's rare bright paths left the 1% bound to the
// seeds' luck (4 sigma 1.1-1.4% on two of three sets of seeds, in RGB mode too).
TEST(HairRender, PathLightAndBdptAgree) {
    expectAgreement(AgreementCase{"hair", kScene, {"path", "light", "bdpt"}, 32, 16, {{"light", 128}}});
}
