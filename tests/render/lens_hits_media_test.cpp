// The t = 0 strategy in participating media (lens_hits.h, subpaths_media.cpp; thesis §10.2):
// a light walk's free flight that passes the thin lens before it collides records the
// crossing, its throughput carrying the flight's transmittance estimate to the lens and its
// spectral-MIS ratios. Two checks: a point light seen in a flat mirror through absorbing,
// chromatic fog, sampled by t = 0 alone, against its closed form (the fog-free one of
// docs/unsampled-paths.md with the transmittance along the path); and a small area light in
// scattering fog seen in the mirror, where t = 0 is weighted against the other strategies,
// by BDPT with and without it and by path tracing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "spectral_answer.h"
#include "transport/bdpt.h"

using namespace ps;
using namespace ps::test;

namespace {

// Each channel's mean of the whole image over independent renders (seeds seed0 ...), with
// its standard error measured across them. `lensHits` false: BDPT without t = 0.
struct ChannelMeans {
    double mean[3] = {0, 0, 0}, se[3] = {0, 0, 0};
};
ChannelMeans measure(const std::string& text, const std::string& integrator, int spp, int renders, uint64_t seed0,
                     bool lensHits = true) {
    const bool spectral = defaultSpectral();
    setWarningsQuiet(true);
    auto scene = buildScene(parseSceneString(text, ".", "<test>"), spectral);
    scene->settings().spectral = spectral;
    auto integ = createIntegrator(integrator, *scene);
    if (!lensHits) {
        auto* bdpt = dynamic_cast<BDPTIntegrator*>(integ.get());
        EXPECT_NE(bdpt, nullptr);
        if (bdpt) bdpt->disableLensHits();
    }
    double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
    for (int k = 0; k < renders; ++k) {
        RenderOptions opts;
        opts.spp = spp;
        opts.seed = seed0 + uint64_t(k);
        opts.sampler = scene->settings().sampler;
        opts.progress = false;
        const RegionStats r = wholeImage(render(*scene, *integ, opts).image);
        for (int c = 0; c < 3; ++c) {
            s[c] += r.mean[c];
            s2[c] += r.mean[c] * r.mean[c];
        }
    }
    ChannelMeans m;
    for (int c = 0; c < 3; ++c) {
        m.mean[c] = s[c] / renders;
        m.se[c] = std::sqrt(std::max(0.0, (s2[c] / renders - m.mean[c] * m.mean[c]) / (renders - 1)));
    }
    std::printf("  %-6s%s %.5f %.5f %.5f +- %.5f %.5f %.5f (%d renders of %d spp)\n", integrator.c_str(),
                lensHits ? "    " : " -t0", m.mean[0], m.mean[1], m.mean[2], m.se[0], m.se[1], m.se[2], renders, spp);
    return m;
}

// a and b agree per channel within 4 sigma (their errors combined), and 4 sigma resolves
// `resolution` of b (0: not asked).
void expectAgree(const ChannelMeans& a, const ChannelMeans& b, const std::string& what, double resolution) {
    for (int c = 0; c < 3; ++c) {
        const double sigma = std::hypot(a.se[c], b.se[c]);
        std::printf("  %s, channel %d: %+.2f sigma (4 sigma = %.2f%%)\n", what.c_str(), c,
                    (a.mean[c] - b.mean[c]) / sigma, 400 * sigma / b.mean[c]);
        EXPECT_NEAR(a.mean[c], b.mean[c], 4 * sigma)
            << what << " channel " << c << ": " << (a.mean[c] - b.mean[c]) / sigma << " sigma";
        if (resolution > 0)
            EXPECT_LT(4 * sigma, resolution * b.mean[c]) << what << " channel " << c << ": cannot resolve it";
    }
}

// ---- a point light in a mirror, through absorbing fog ----
// The scene of lens_hits_test.cpp (the camera at the origin looking down -z through a lens of
// radius r; the mirror at z = -zm; the light behind the lens at z = +zl, its mirror image on
// the axis at D = 2 zm + zl), all of it in fog that absorbs and does not scatter: the light's
// only paths are L S E, which t = 0 alone samples.
constexpr double kLensRadius = 0.25, kMirror = 0.375, kLightZ = 0.25, kFov = 40;
constexpr float kSigmaA[3] = {0.3f, 0.7f, 1.2f};

std::string absorbingFogScene(const char* integrator) {
    char text[1400];
    std::snprintf(text, sizeof text,
                  "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ %g %g %g ] "
                  "\"rgb sigma_s\" [ 0 0 0 ]\n"
                  "MediumInterface \"fog\" \"fog\"\n"
                  "LookAt 0 0 0  0 0 -1  0 1 0\n"
                  "Camera \"perspective\" \"float fov\" [ %g ] \"float lensradius\" [ %g ] \"float focaldistance\" [ 2 ]\n"
                  "Film \"rgb\" \"integer xresolution\" [ 48 ] \"integer yresolution\" [ 48 ]\n"
                  "PixelFilter \"box\"\nSampler \"independent\"\n"
                  "Integrator \"%s\" \"integer maxdepth\" [ 3 ]\nWorldBegin\n"
                  "MediumInterface \"fog\" \"fog\"\n"
                  "AttributeBegin\nMaterial \"conductor\" \"rgb reflectance\" [ 1 1 1 ] \"float roughness\" [ 0 ]\n"
                  "Shape \"trianglemesh\" \"point3 P\" [ -4 -4 %g  4 -4 %g  4 4 %g  -4 4 %g ] "
                  "\"integer indices\" [ 0 1 2 0 2 3 ]\nAttributeEnd\n"
                  "LightSource \"point\" \"rgb I\" [ 1 1 1 ] \"point3 from\" [ 0 0 %g ]\n",
                  kSigmaA[0], kSigmaA[1], kSigmaA[2], kFov, kLensRadius, integrator, -kMirror, -kMirror, -kMirror,
                  -kMirror, kLightZ);
    return text;
}

// The image mean per unit intensity at absorption coefficient sigma: the fog-free integrand
// over the lens (docs/unsampled-paths.md), R I / (A pi r^2) * 2 pi rho d / D^3 at lens radius
// rho, d = sqrt(D^2 + rho^2) the path's length from the mirror image, times its transmittance
// exp(-sigma d). Simpson's rule over rho.
double exactMean(double I, double sigma) {
    const double r = kLensRadius, D = 2 * kMirror + kLightZ, R = 0.9999;
    const double t = std::tan(kFov * M_PI / 360), A = 4 * t * t;
    const int n = 2000;
    double sum = 0;
    for (int i = 0; i <= n; ++i) {
        const double rho = r * i / n, d = std::sqrt(D * D + rho * rho);
        const double w = i == 0 || i == n ? 1 : i % 2 ? 4 : 2;
        sum += w * 2 * M_PI * rho * d / (D * D * D) * std::exp(-sigma * d);
    }
    return R * I / (A * M_PI * r * r) * sum * r / (3 * n);
}

// ---- a small area light in scattering fog, seen in a mirror ----
// The scene above with a small disk light facing the mirror in place of the point light
// (behind the lens, seen only in the mirror) and fog that scatters, chromatically: the light
// reaches the lens straight from the mirror (L S E, where t = 0 carries most of the image:
// the lens is 25 times the disk's area) and after scatterings in the fog, where t = 0 is
// weighted against the camera subpaths that find the disk and the connections to the lens.
const char* kScatteringFog = R"(
MakeNamedMedium "fog" "string type" "homogeneous" "rgb sigma_a" [ 0.05 0.1 0.2 ]
  "rgb sigma_s" [ 0.4 0.3 0.15 ] "float g" [ 0.5 ]
MediumInterface "fog" "fog"
LookAt 0 0 0  0 0 -1  0 1 0
Camera "perspective" "float fov" [ 40 ] "float lensradius" [ 0.25 ] "float focaldistance" [ 2 ]
Film "rgb" "integer xresolution" [ 32 ] "integer yresolution" [ 32 ]
PixelFilter "box"
Sampler "independent"
Integrator "bdpt" "integer maxdepth" [ 3 ]
WorldBegin
MediumInterface "fog" "fog"
AttributeBegin
  Material "conductor" "rgb reflectance" [ 0.9 0.8 0.6 ] "float roughness" [ 0 ]
  Shape "trianglemesh" "point3 P" [ -4 -4 -0.375  4 -4 -0.375  4 4 -0.375  -4 4 -0.375 ]
    "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [ 60 60 60 ]
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  Translate 0.1 0.05 0.25
  Rotate 180 0 1 0
  Shape "disk" "float radius" [ 0.05 ]
AttributeEnd
)";

}  // namespace

// BDPT (t = 0 is the only strategy of these paths) and light tracing against the closed form,
// each channel within 4 sigma, where 4 sigma resolves 2%; and against each other.
TEST(LensHitsInMedia, PointLightInAMirrorThroughAbsorbingFog) {
    const Lifted I = emission({1, 1, 1});
    const Lifted sigma{{kSigmaA[0], kSigmaA[1], kSigmaA[2]},
                       SpectrumSource::rgbUnbounded(srgbColorSpace(), {kSigmaA[0], kSigmaA[1], kSigmaA[2]})};
    const std::array<double, 3> exact = exactPixel(defaultSpectral(), exactMean, I, sigma);
    std::printf("  exact  %.5f %.5f %.5f\n", exact[0], exact[1], exact[2]);
    ChannelMeans exactMeans;
    for (int c = 0; c < 3; ++c) exactMeans.mean[c] = exact[c];
    const ChannelMeans bdpt = measure(absorbingFogScene("bdpt"), "bdpt", 224, 24, 300);
    const ChannelMeans light = measure(absorbingFogScene("light"), "light", 224, 24, 700);
    expectAgree(bdpt, exactMeans, "bdpt against the closed form", 0.02);
    expectAgree(light, exactMeans, "light against the closed form", 0.02);
    expectAgree(bdpt, light, "bdpt against light", 0);
}

// BDPT with t = 0 weighted in (84% of this image by --stats' figures: s3_t0 0.81, s4_t0
// 0.03), BDPT without it and path tracing agree: t = 0's estimates in the fog (the flight's
// transmittance to the lens, its spectral MIS) and its MIS weights against the other
// strategies.
TEST(LensHitsInMedia, AreaLightInScatteringFogWithAndWithoutTZero) {
    // The light in the mirror is a small, bright target for every technique: 4 sigma resolves
    // 4% here (measured 1.9-3.4%), where t = 0 carries most of the image through fog of
    // transmittance about 0.85 from the mirror to the lens (without it bdpt came out 14%
    // bright, +23 sigma).
    const ChannelMeans path = measure(kScatteringFog, "path", 384, 16, 100);
    const ChannelMeans with = measure(kScatteringFog, "bdpt", 64, 16, 300);
    const ChannelMeans without = measure(kScatteringFog, "bdpt", 96, 16, 500, false);
    expectAgree(with, path, "bdpt against path", 0.04);
    expectAgree(without, path, "bdpt without t = 0 against path", 0.04);
    expectAgree(with, without, "bdpt with t = 0 against bdpt without", 0.04);
}

// A few samples of both scenes, for the sanitizer suite (which skips the two agreements above
// for their cost): the lens crossings in absorbing and scattering fog run, and give a finite,
// positive image.
TEST(LensHitsInMedia, FewSamplesRunUnderTheSanitizers) {
    for (const auto& [text, integrator] : {std::pair<std::string, const char*>{absorbingFogScene("bdpt"), "bdpt"},
                                           {absorbingFogScene("light"), "light"},
                                           {kScatteringFog, "bdpt"}}) {
        const ChannelMeans m = measure(text, integrator, 2, 2, 7);
        for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(std::isfinite(m.mean[c])) << integrator;
            EXPECT_GT(m.mean[c], 0) << integrator;
        }
    }
}
