// Spectral mode (--color spectral, math/spectrum.h): the film's conversion from sampled
// wavelengths to colour, the white furnace, dispersion's termination of the secondary
// wavelengths, and every integrator's white furnace.
#include <gtest/gtest.h>

#include <random>

#include "../app/furnace_scene.h"
#include "mc/estimator.h"
#include "render_helpers.h"
#include "spectral/sampled_spectrum.h"
#include "transport/spectral_film.h"

using namespace ps;
using namespace ps::test;

namespace {

RenderResult renderSpectral(const std::string& text, int spp, const std::string& integrator = "", uint64_t seed = 7) {
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(text, ".", "<test>");
    auto scene = buildScene(desc);
    if (!integrator.empty()) scene->settings().integrator = integrator;
    scene->settings().spectral = true;
    auto integ = createIntegrator(scene->settings().integrator, *scene);
    RenderOptions opts;
    opts.spp = spp;
    opts.seed = seed;
    opts.sampler = scene->settings().sampler;
    opts.progress = false;
    return render(*scene, *integ, opts);
}

// Every pixel an independent estimate of `value` in every channel.
void expectUniform(const Image& img, double value, double maxRelativeError) {
    RegionStats s = regionStats(img, 0, img.width, 0, img.height);
    for (int c = 0; c < 3; ++c) {
        std::printf("  channel %d: %.5f +- %.5f (exact %.5f)\n", c, s.mean[c], s.stdErr[c], value);
        EXPECT_NEAR(s.mean[c], value, 4 * s.stdErr[c]) << c;
        EXPECT_LT(s.stdErr[c], maxRelativeError * value) << c;
    }
}

}  // namespace

// A constant RGB reflectance lifted to a spectrum (Jakob-Hanika table), lit by the colour
// space's white (RGB (1,1,1) lifted as an illuminant), sampled at many wavelength sets and
// pushed through the film's conversion, averages back to the RGB: to the table's stated
// accuracy for sRGB (1e-3, tests/spectral/rgb_to_spectrum_test.cpp) beyond 4 standard errors.
TEST(SpectralFilm, ConstantReflectanceAveragesBackToItsRGB) {
    RenderSettings settings;
    const SpectralFilm film(settings);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> U(0, 1);
    for (Spectrum rgb : {Spectrum(0.5f), Spectrum(0.8f, 0.3f, 0.1f), Spectrum(0.1f, 0.6f, 0.9f), Spectrum(0.95f, 0.9f, 0.05f),
                         Spectrum(0.02f, 0.02f, 0.5f)}) {
        RunningStats c[3];
        for (int k = 0; k < 200000; ++k) {
            const SampledWavelengths w = SpectralFilm::sampleWavelengths(U(rng));
            const Spectrum L = liftAlbedo(rgb, w) * liftIlluminant(Spectrum(1.0f), w);
            const Spectrum out = film.toRendering(L, w);
            for (int i = 0; i < 3; ++i) c[i].add(out[i]);
        }
        for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(c[i].mean(), rgb[i], 1e-3 + 4 * c[i].standardError()) << rgb.r << " " << rgb.g << " " << rgb.b << " channel " << i;
            EXPECT_LT(c[i].standardError(), 2e-3);
        }
    }
}

// Terminated wavelengths (pdf 0) contribute nothing; the survivor carries four times the
// weight (SampledWavelengths::terminateSecondary), so the estimate stays unbiased.
TEST(SpectralFilm, TerminatedWavelengthsKeepTheMean) {
    const SpectralFilm film{RenderSettings{}};
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> U(0, 1);
    RunningStats all[3], hero[3];
    for (int k = 0; k < 200000; ++k) {
        SampledWavelengths w = SpectralFilm::sampleWavelengths(U(rng));
        const Spectrum L = liftIlluminant(Spectrum(0.3f, 0.5f, 0.9f), w);
        const Spectrum a = film.toRendering(L, w);
        w.terminateSecondary();
        const Spectrum h = film.toRendering(L, w);
        for (int i = 0; i < 3; ++i) {
            all[i].add(a[i]);
            hero[i].add(h[i]);
        }
    }
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(hero[i].mean(), all[i].mean(), 4 * std::hypot(hero[i].standardError(), all[i].standardError())) << i;
}

// The closed furnace: grey walls, white emission. Spectrally each sample has a colour (its
// wavelengths'), the image is white at the exact value, in every channel: by path tracing,
// by light tracing (every value a splat, converted at the splat), by BDPT and by Veach's mlt
// (the wavelengths part of its state). Sigma across 8 renders (a light path splats onto
// several pixels, a chain's samples are correlated: pixels are not independent).
TEST(SpectralMode, WhiteFurnaceStaysWhite) {
    for (const char* integrator : {"path", "light", "bdpt", "mlt"}) {
        RunningStats channel[3];
        for (int k = 0; k < 8; ++k) {
            // Light tracing varies more; a chain's samples are correlated.
            const int spp = std::string(integrator) == "light" ? 384 : std::string(integrator) == "mlt" ? 256 : 64;
            const RegionStats s = wholeImage(renderSpectral(kFurnace, spp, integrator, 20 + uint64_t(k)).image);
            for (int c = 0; c < 3; ++c) channel[c].add(s.mean[c]);
        }
        for (int c = 0; c < 3; ++c) {
            std::printf("  %s channel %d: %.5f +- %.5f (exact %.5f)\n", integrator, c, channel[c].mean(),
                        channel[c].standardError(), kFurnaceValue);
            EXPECT_NEAR(channel[c].mean(), kFurnaceValue, 4 * channel[c].standardError()) << integrator << " " << c;
            EXPECT_LT(channel[c].standardError(), 0.0025 * kFurnaceValue) << integrator << " " << c << ": too noisy";
        }
    }
}

// A dispersive glass sphere (BK7) in a uniform white sky is invisible: a lossless dielectric
// under uniform radiance returns it along every ray. Each refraction keeps only the first
// wavelength with four times its weight; were that weight lost, the sphere would be dark.
TEST(SpectralMode, DispersiveGlassInUniformLightIsInvisible) {
    const char* scene = R"(LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" [ 20 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
Integrator "path" "integer maxdepth" [ 64 ]
PixelFilter "box"
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
Material "dielectric" "spectrum eta" "glass-BK7"
Shape "sphere" "float radius" [ 1 ]
)";
    for (const char* integrator : {"path", "bdpt"}) {
        SCOPED_TRACE(integrator);
        std::printf(" %s\n", integrator);
        RenderResult r = renderSpectral(scene, 64, integrator);
        expectUniform(r.image, 1.0, 0.01);
    }
}
