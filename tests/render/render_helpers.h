// Shared helpers for statistical render tests: render a scene string and summarise a
// region of pixels. In a region where the exact image is constant, pixels are independent
// estimates of the same value, so their spread gives the standard error of the mean.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "mc/sampler.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "transport/renderer.h"
#include "util/error.h"

namespace ps::test {

// The colour mode of a render whose test does not choose one: RGB, or spectral when the
// environment has PATHSPACE_TEST_COLOR=spectral. CTest runs the render tests in both modes
// (tests/CMakeLists.txt), so that what holds in one is checked in the other.
inline bool defaultSpectral() {
    const char* mode = std::getenv("PATHSPACE_TEST_COLOR");
    return mode && std::string(mode) == "spectral";
}

// Renders with `options`, taking the sampler from the scene; progress off. The integrator
// may name a variant (applyIntegratorVariant: "mlt:lens=0", "mmlt:two-stage=0.25"). `spectral`: --color spectral (unset: the
// tests' default mode).
inline RenderResult renderWith(const std::string& text, RenderOptions opts, const std::string& integrator = "",
                               std::optional<bool> spectralMode = std::nullopt) {
    const bool spectral = spectralMode.value_or(defaultSpectral());
    setWarningsQuiet(true);
    SceneDescription desc = parseSceneString(text, ".", "<test>");
    auto scene = buildScene(desc, spectral);
    if (!integrator.empty()) scene->settings().integrator = applyIntegratorVariant(integrator, scene->settings());
    // The Metropolis tests check the plain target unless they name two-stage MLT (the
    // renderer's default), which has tests of its own.
    if (integrator.find("two-stage=") == std::string::npos) scene->settings().mltTwoStage = 0;
    scene->settings().spectral = spectral;
    auto integ = createIntegrator(scene->settings().integrator, *scene);
    opts.sampler = scene->settings().sampler;
    opts.progress = false;
    return render(*scene, *integ, opts);
}

inline RenderResult renderString(const std::string& text, int spp, uint64_t seed = 7, int threads = 0,
                                 const std::string& integrator = "", std::optional<bool> spectral = std::nullopt) {
    RenderOptions opts;
    opts.spp = spp;
    opts.seed = seed;
    opts.threads = threads;
    return renderWith(text, opts, integrator, spectral);
}

// The closed furnace: a camera at the centre of a unit sphere, seen from inside, that emits
// "rgb L" `L` and reflects diffusely with albedo `albedo` (an RGB triple, "0.6 0.6 0.6");
// 16 x 16 pixels, box filter. Its pixel is L sum_{k <= maxDepth} albedo^k.
inline std::string closedFurnaceScene(int maxDepth, const std::string& L, const std::string& albedo) {
    return R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 60 ]
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        PixelFilter "box"
        Integrator "path" "integer maxdepth" [ )" +
           std::to_string(maxDepth) + R"( ]
        WorldBegin
        AreaLightSource "diffuse" "rgb L" [ )" +
           L + R"( ]
        Material "diffuse" "rgb reflectance" [ )" +
           albedo + R"( ]
        ReverseOrientation
        Shape "sphere" "float radius" [ 1 ]
    )";
}

// Pixels of two images of one size that differ in any bit, and pixels of the first that are
// not finite.
struct PixelComparison {
    int differ = 0, nonFinite = 0;
};
inline PixelComparison comparePixels(const Image& a, const Image& b) {
    PixelComparison c;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const Spectrum p = a.get(x, y), q = b.get(x, y);
            c.differ += (p.r != q.r || p.g != q.g || p.b != q.b);
            c.nonFinite += !p.isFinite();
        }
    return c;
}

struct RegionStats {
    double mean[3] = {0, 0, 0};
    double stdErr[3] = {0, 0, 0};
    int n = 0;
};

inline RegionStats regionStats(const Image& img, int x0, int x1, int y0, int y1) {
    RegionStats r;
    double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            Spectrum v = img.get(x, y);
            for (int c = 0; c < 3; ++c) {
                s[c] += v[c];
                s2[c] += double(v[c]) * v[c];
            }
            ++r.n;
        }
    for (int c = 0; c < 3; ++c) {
        r.mean[c] = s[c] / r.n;
        double var = std::max(0.0, (s2[c] / r.n - r.mean[c] * r.mean[c]) * r.n / (r.n - 1));
        r.stdErr[c] = std::sqrt(var / r.n);
    }
    return r;
}

inline RegionStats wholeImage(const Image& img) { return regionStats(img, 0, img.width, 0, img.height); }

// The mean luminance (Rec. 709 weights) of a whole image.
inline double luminanceMean(const Image& img) {
    RegionStats s = wholeImage(img);
    return 0.2126 * s.mean[0] + 0.7152 * s.mean[1] + 0.0722 * s.mean[2];
}

// The largest of X, Y, Z of a linear sRGB colour (IEC 61966-2-1's matrix, to 4 digits): what
// Film "maxcomponentvalue" clamps (pbrt-v4's cie1931 sensor measures X, Y, Z).
inline double largestXYZ(Spectrum c) {
    const double x = 0.4124 * c.r + 0.3576 * c.g + 0.1805 * c.b, y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b,
                 z = 0.0193 * c.r + 0.1192 * c.g + 0.9505 * c.b;
    return std::max(x, std::max(y, z));
}

// The path depth s + t - 2 of a BDPT strategy image named "s<S>_t<T>[...]", or -1.
inline int strategyDepth(const std::string& name) {
    int s = 0, t = 0;
    return std::sscanf(name.c_str(), "s%d_t%d", &s, &t) == 2 ? s + t - 2 : -1;
}

}  // namespace ps::test

namespace ps::test {

// Luminance of B x B blocks of pixels, averaged over K independent renders (seeds seed0..);
// the spread across renders gives each block's standard error without assuming that
// pixels within a block share one value. The whole image's luminance is summarised the same
// way (its standard error is far smaller than a block's, which makes it the sharper test of
// a global bias).
struct BlockMeans {
    std::vector<double> mean, stdErr;
    double imageMean = 0, imageStdErr = 0;
    double channelMean[3] = {0, 0, 0}, channelStdErr[3] = {0, 0, 0};  // the image's R, G, B
    std::vector<double> blockChannelMean[3], blockChannelStdErr[3];     // each block's R, G, B
};

inline BlockMeans blockMeans(const std::string& scene, const std::string& integrator, int spp, int renders,
                             int blocksPerSide, uint64_t seed0 = 100, std::optional<bool> spectral = std::nullopt) {
    std::vector<double> s, s2, bc[3], bc2[3];
    double is = 0, is2 = 0, cs[3] = {0, 0, 0}, cs2[3] = {0, 0, 0};
    for (int k = 0; k < renders; ++k) {
        RenderResult r = renderString(scene, spp, seed0 + uint64_t(k), 0, integrator, spectral);
        RegionStats whole = wholeImage(r.image);
        double iy = 0.2126 * whole.mean[0] + 0.7152 * whole.mean[1] + 0.0722 * whole.mean[2];
        is += iy;
        is2 += iy * iy;
        for (int c = 0; c < 3; ++c) {
            cs[c] += whole.mean[c];
            cs2[c] += whole.mean[c] * whole.mean[c];
        }
        int bw = r.image.width / blocksPerSide, bh = r.image.height / blocksPerSide;
        s.resize(size_t(blocksPerSide) * blocksPerSide, 0.0);
        s2.resize(s.size(), 0.0);
        for (int c = 0; c < 3; ++c) {
            bc[c].resize(s.size(), 0.0);
            bc2[c].resize(s.size(), 0.0);
        }
        for (int by = 0; by < blocksPerSide; ++by)
            for (int bx = 0; bx < blocksPerSide; ++bx) {
                RegionStats rs = regionStats(r.image, bx * bw, bx * bw + bw, by * bh, by * bh + bh);
                double y = 0.2126 * rs.mean[0] + 0.7152 * rs.mean[1] + 0.0722 * rs.mean[2];
                s[size_t(by) * blocksPerSide + bx] += y;
                s2[size_t(by) * blocksPerSide + bx] += y * y;
                for (int c = 0; c < 3; ++c) {
                    bc[c][size_t(by) * blocksPerSide + bx] += rs.mean[c];
                    bc2[c][size_t(by) * blocksPerSide + bx] += rs.mean[c] * rs.mean[c];
                }
            }
    }
    BlockMeans b;
    for (size_t i = 0; i < s.size(); ++i) {
        double m = s[i] / renders;
        double var = std::max(0.0, (s2[i] / renders - m * m) * renders / (renders - 1));
        b.mean.push_back(m);
        b.stdErr.push_back(std::sqrt(var / renders));
    }
    auto meanAndError = [&](double sum, double sum2, double& mean, double& stdErr) {
        mean = sum / renders;
        stdErr = std::sqrt(std::max(0.0, (sum2 / renders - mean * mean) / (renders - 1)));
    };
    meanAndError(is, is2, b.imageMean, b.imageStdErr);
    for (int c = 0; c < 3; ++c) {
        b.blockChannelMean[c].resize(s.size());
        b.blockChannelStdErr[c].resize(s.size());
        for (size_t i = 0; i < s.size(); ++i)
            meanAndError(bc[c][i], bc2[c][i], b.blockChannelMean[c][i], b.blockChannelStdErr[c][i]);
    }
    for (int c = 0; c < 3; ++c) meanAndError(cs[c], cs2[c], b.channelMean[c], b.channelStdErr[c]);
    return b;
}

}  // namespace ps::test
