// The scenes and checks the medium-emission tests share (medium_emission_test.cpp,
// medium_emission_input_test.cpp): a camera inside a glowing, purely absorbing medium, whose
// radiance is exact, and the comparison of renders with an exact answer.
#pragma once
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "media_test_helpers.h"
#include "render_helpers.h"
#include "spectral_answer.h"

namespace ps::test {

// The camera at the centre of an `interface` sphere of radius 1 (nothing beyond it), filled
// with medium "glow" (`medium`: MakeNamedMedium's parameters), which absorbs sigma_a
// (0.5, 1, 2), scatters nothing and emits Le (1, 0.8, 0.6): every ray sees
// Le (1 - exp(-sigma_a)), per channel (per wavelength in spectral mode).
inline std::string glowingSphere(const std::string& integrator, int maxDepth,
                                 const std::string& medium = R"("string type" "homogeneous" "rgb sigma_a" [ 0.5 1 2 ]
  "rgb sigma_s" [ 0 0 0 ] "rgb Le" [ 1 0.8 0.6 ])") {
    return "MakeNamedMedium \"glow\" " + medium + R"(
MediumInterface "" "glow"
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" [ 60 ]
Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
PixelFilter "box"
Sampler "independent"
Integrator ")" + integrator + R"(" "integer maxdepth" [ )" + std::to_string(maxDepth) + R"( ] )" +
           // A tenth of the default bootstrap: stratified, it resolves b well within 2% here.
           (integrator == "pssmlt" || integrator == "mmlt" ? "\"integer bootstrapsamples\" [ 10000 ]" : "") + R"(
WorldBegin
Material "interface"
MediumInterface "glow" ""
Shape "sphere" "float radius" [ 1 ]
)";
}

inline std::array<double, 3> glowingSphereExact(bool spectral) {
    const std::array<float, 3> sigmaA{0.5f, 1.0f, 2.0f};
    const Lifted sigma{sigmaA, SpectrumSource::rgbUnbounded(srgbColorSpace(), sigmaA), 1};
    return exactPixel(spectral, [](double L, double s) { return L * (1 - std::exp(-s)); }, emission({1.0f, 0.8f, 0.6f}),
                      sigma);
}

// The image's channel means and luminance over `renders` independent renders (their spread
// gives sigma, also for Metropolis, whose pixels are correlated and whose normalisation b is
// one estimate per render) against `exact`: each within 4 sigma, and the luminance's sigma
// small enough to catch a 2% error.
inline void expectRendersMatch(const std::string& scene, const std::string& integrator, int spp, int renders,
                        const std::array<double, 3>& exact) {
    const BlockMeans b = blockMeans(scene, integrator, spp, renders, 1);
    for (int c = 0; c < 3; ++c) {
        std::printf("[ %-8s ] channel %d: %.5f +- %.5f, exact %.5f, ratio %.4f, %+.2f sigma\n", integrator.c_str(), c,
                    b.channelMean[c], b.channelStdErr[c], exact[c], b.channelMean[c] / exact[c],
                    (b.channelMean[c] - exact[c]) / std::max(1e-12, b.channelStdErr[c]));
        EXPECT_NEAR(b.channelMean[c], exact[c], 4 * b.channelStdErr[c] + kSpectralSystematic * exact[c])
            << integrator << " channel " << c;
    }
    const double y = 0.2126 * exact[0] + 0.7152 * exact[1] + 0.0722 * exact[2];
    std::printf("[ %-8s ] luminance: %.5f +- %.5f, exact %.5f, ratio %.4f, %+.2f sigma\n", integrator.c_str(), b.imageMean,
                b.imageStdErr, y, b.imageMean / y, (b.imageMean - y) / std::max(1e-12, b.imageStdErr));
    EXPECT_NEAR(b.imageMean, y, 4 * b.imageStdErr + kSpectralSystematic * y) << integrator;
    EXPECT_LT(4 * b.imageStdErr, 0.02 * y) << integrator << ": cannot resolve 2%";
}

}  // namespace ps::test
