// Writes the synthetic measured BRDF of tests/data/pbrt-v4/spectral-materials.pbrt: a GGX
// reflector (alpha 0.25) tabulated in the RGL .bsdf format by measured_tensor_writer.h, with a
// reflectance spectrum that varies over 400-700 nm (high in blue and red, low in green), so
// that pbrt-v4 and pathspace must interpolate it at each wavelength alike.
//   make_measured_bsdf OUT.bsdf
#include <cstdio>

#include "materials/measured_tensor_writer.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_measured_bsdf OUT.bsdf\n");
        return 2;
    }
    ps::test::GgxTableSpec spec;
    spec.alpha = 0.25f;
    spec.n = 20;
    spec.nTheta = 10;
    spec.wavelengths = {400, 450, 500, 550, 600, 650, 700};
    spec.spectrum = {0.9f, 0.7f, 0.4f, 0.3f, 0.45f, 0.75f, 0.95f};
    ps::test::writeBytes(argv[1], ps::test::tensorFileBytes(ps::test::ggxTensorFields(spec)));
    return 0;
}
