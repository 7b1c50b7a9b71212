// Material "measured" in a render: light tracing and BDPT agree with the path tracer, and
// so does multiplexed Metropolis (agreement.h), on a glossy measured floor (a GGX reflector
// tabulated by materials/measured_tensor_writer.h) under a point light, with a diffuse ball;
// in spectral mode with a file whose spectra vary with the wavelength, and with an RGB file
// (lifted per lookup).
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include "agreement.h"
#include "materials/measured_tensor_writer.h"

using namespace ps;
using namespace ps::test;
namespace fs = std::filesystem;

namespace {

// The generated file in a temporary directory, removed with the object.
struct MeasuredFile {
    fs::path dir = fs::temp_directory_path() / ("pathspace-measured-render-" + std::to_string(getpid()));
    std::string file = (dir / "ggx.bsdf").string();
    explicit MeasuredFile(const GgxTableSpec& spec = GgxTableSpec{}) {
        fs::create_directories(dir);
        writeBytes(file, tensorFileBytes(ggxTensorFields(spec)));
    }
    ~MeasuredFile() { fs::remove_all(dir); }
};

std::string scene(const std::string& file, const std::string& integrator) {
    return R"(LookAt 0 1.6 2  0 0.2 0  0 1 0
        Camera "perspective" "float fov" [ 45 ]
        Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]
        PixelFilter "box"
        )" + integrator + R"(
        WorldBegin
        LightSource "point" "rgb I" [ 3 3 3 ] "point3 from" [ 0.3 1.2 -0.4 ]
        Material "measured" "string filename" [ ")" + file + R"(" ]
        Shape "bilinearmesh" "point3 P" [ -1.5 0 1.5  1.5 0 1.5  -1.5 0 -1.5  1.5 0 -1.5 ]
        AttributeBegin
          Material "diffuse" "rgb reflectance" [ 0.8 0.4 0.2 ]
          Translate -0.3 0.3 0
          Shape "sphere" "float radius" [ 0.3 ]
        AttributeEnd
    )";
}

}  // namespace

TEST(MeasuredRender, LightTracingAndBdptAgreeWithPathTracing) {
    MeasuredFile m;
    expectAgreement(AgreementCase{"measured floor", scene(m.file, R"(Integrator "path" "integer maxdepth" [ 3 ])"),
                                  {"path", "light", "bdpt"}, 16, 16, {{"light", 128}}});
}

TEST(MeasuredRender, MetropolisAgreesWithPathTracing) {
    MeasuredFile m;
    std::string mlt = R"(Integrator "mmlt" "integer maxdepth" [ 3 ] "integer chains" [ 64 ] "integer bootstrapsamples" [ 10000 ])";
    expectAgreement(AgreementCase{"measured floor", scene(m.file, mlt), {"path", "mmlt"}, 16, 16, {{"mmlt", 48}}});
}

// A reddish spectrum tabulated over 400-700 nm (constant beyond, as the interpolant holds its
// ends), read at each path's wavelengths.
GgxTableSpec spectralSpec() {
    GgxTableSpec s;
    s.wavelengths = {400, 450, 500, 550, 600, 650, 700};
    s.spectrum = {0.15f, 0.2f, 0.3f, 0.5f, 0.8f, 0.9f, 0.95f};
    return s;
}

TEST(MeasuredRender, SpectralLightTracingAndBdptAgreeWithPathTracing) {
    for (const GgxTableSpec& spec : {spectralSpec(), GgxTableSpec{}}) {
        MeasuredFile m(spec);
        AgreementCase c{spec.wavelengths.empty() ? "spectral, rgb file" : "spectral, spectral file",
                        scene(m.file, R"(Integrator "path" "integer maxdepth" [ 3 ])"), {"path", "light", "bdpt"}, 32, 16,
                        {{"light", 192}}};
        c.spectral = true;
        expectAgreement(c);
    }
}
