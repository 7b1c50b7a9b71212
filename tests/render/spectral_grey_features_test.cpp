// Grey scenes render alike in both colour modes: with every reflectance grey and every light
// white, each path's spectrum is the illuminant times a constant, which the sensor maps to
// equal r, g, b, so the spectral image equals the RGB image in expectation. Checked here for
// the features whose spectral evaluation is their own code: a goniometric light (white I,
// grey map), a projection light (grey slide), hair (grey sigma_a and grey reflectance) and a
// measured material (a file with a flat spectrum, against its RGB conversion). Each channel's
// image mean and each block's luminance within 4 sigma, sigma from independent renders.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "materials/measured_tensor_writer.h"
#include "mc/rng.h"
#include "render_helpers.h"
#include "temp_images.h"

using namespace ps;
using namespace ps::test;

namespace {

const char* kHeader = R"(LookAt 0 2 2.2  0 0.2 0  0 1 0
    Camera "perspective" "float fov" [ 40 ]
    Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
    PixelFilter "box"
    Integrator "path" "integer maxdepth" [ 3 ]
    WorldBegin
)";

const char* kGroundAndBall = R"(
    Material "diffuse" "rgb reflectance" [ 0.6 0.6 0.6 ]
    Shape "bilinearmesh" "point3 P" [ -1.5 0 1.5  1.5 0 1.5  -1.5 0 -1.5  1.5 0 -1.5 ]
    AttributeBegin
      Material "diffuse" "rgb reflectance" [ 0.3 0.3 0.3 ]
      Translate 0.1 0.3 -0.1
      Shape "sphere" "float radius" [ 0.3 ]
    AttributeEnd
)";

const char* kWhiteLight = R"(
    AttributeBegin
      AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]
      Shape "bilinearmesh" "point3 P" [ -0.4 1.5 -0.4   0.4 1.5 -0.4   -0.4 1.5 0.4   0.4 1.5 0.4 ]
    AttributeEnd
)";

// A grey image with a random bright texel here and there.
Image greyPattern(int w, int h, uint64_t seed) {
    Image img(w, h);
    Rng rng(seed);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float v = 0.2f + 0.7f * float(x + y) / float(w + h);
            img.set(x, y, Spectrum(rng.uniform() < 0.1f ? 5 * v : v));
        }
    return img;
}

void expectSameInBothModes(const char* name, const std::string& scene, int spp) {
    const int renders = 12, blocks = 4;
    BlockMeans rgb = blockMeans(scene, "path", spp, renders, blocks, 100, false);
    BlockMeans spectral = blockMeans(scene, "path", spp, renders, blocks, 200, true);
    ASSERT_GT(rgb.imageMean, 0.01) << name << ": the scene must be lit";
    for (int c = 0; c < 3; ++c) {
        double se = std::hypot(rgb.channelStdErr[c], spectral.channelStdErr[c]);
        double z = (spectral.channelMean[c] - rgb.channelMean[c]) / se;
        std::printf("  %s: channel %d: rgb %.5f +- %.5f spectral %.5f +- %.5f (ratio %.4f, %+.2f sigma)\n", name, c,
                    rgb.channelMean[c], rgb.channelStdErr[c], spectral.channelMean[c], spectral.channelStdErr[c],
                    spectral.channelMean[c] / rgb.channelMean[c], z);
        EXPECT_LT(4 * se, 0.01 * rgb.channelMean[c]) << name << ": too noisy to detect a 1% difference";
        EXPECT_LT(std::fabs(z), 4.0) << name << ": channel " << c;
    }
    double worst = 0;
    for (size_t i = 0; i < rgb.mean.size(); ++i) {
        double se = std::hypot(rgb.stdErr[i], spectral.stdErr[i]);
        double z = std::fabs(spectral.mean[i] - rgb.mean[i]) / std::max(se, 1e-12);
        worst = std::max(worst, z);
        EXPECT_LT(z, 4.0) << name << ": block " << i << ": rgb " << rgb.mean[i] << " spectral " << spectral.mean[i];
    }
    std::printf("  %s: largest block |diff| %.2f sigma\n", name, worst);
}

}  // namespace

TEST(SpectralGreyFeatures, GoniometricLight) {
    TempImages tmp("grey-gonio");
    std::string file = tmp.write("gonio-grey.pfm", greyPattern(16, 16, 3));
    expectSameInBothModes("goniometric", std::string(kHeader) + R"(
        AttributeBegin
          Translate 0.3 1.6 0.4
          Rotate 150 1 0 0.3
          LightSource "goniometric" "float scale" [ 3 ] "string filename" [ ")" + file + R"(" ]
        AttributeEnd
    )" + kGroundAndBall, 64);
}

TEST(SpectralGreyFeatures, ProjectionLight) {
    TempImages tmp("grey-projection");
    std::string file = tmp.write("slide-grey.pfm", greyPattern(8, 6, 4));
    expectSameInBothModes("projection", std::string(kHeader) + R"(
        AttributeBegin
          Translate 0 2 0.8
          Rotate 112 1 0 0
          LightSource "projection" "float fov" [ 40 ] "float scale" [ 4 ] "string filename" [ ")" + file + R"(" ]
        AttributeEnd
    )" + kGroundAndBall, 64);
}

TEST(SpectralGreyFeatures, Hair) {
    expectSameInBothModes("hair", std::string(kHeader) + kWhiteLight + kGroundAndBall + R"(
        Material "hair" "rgb sigma_a" [ 0.5 0.5 0.5 ] "float beta_m" [ 0.35 ] "float beta_n" [ 0.4 ]
        Shape "bilinearmesh" "point3 P" [ -0.8 0.05 0.3   -0.1 0.05 -0.5   -0.8 0.9 0.3   -0.1 0.9 -0.5 ]
        Material "hair" "rgb reflectance" [ 0.4 0.4 0.4 ]
        AttributeBegin
          Translate 0.6 0.35 0.3
          Shape "sphere" "float radius" [ 0.3 ]
        AttributeEnd
    )", 400);
}

TEST(SpectralGreyFeatures, MeasuredMaterial) {
    TempImages tmp("grey-measured");
    GgxTableSpec spec;
    spec.wavelengths = {360, 500, 830};  // a flat spectrum of R.g over the whole range
    const std::string file = (tmp.dir / "flat.bsdf").string();
    writeBytes(file, tensorFileBytes(ggxTensorFields(spec)));
    expectSameInBothModes("measured", std::string(kHeader) + kWhiteLight + R"(
        Material "measured" "string filename" [ ")" + file + R"(" ]
    )" + std::string(kGroundAndBall).substr(std::string(kGroundAndBall).find("Shape")), 64);
}
