// Agreement with pbrt-v4 on small scenes of our own (tests/data/pbrt-v4) against pbrt-v4's
// renders of the same files: shared by pbrt_shapes_reference_test.cpp and
// pbrt_media_reference_test.cpp.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "image/image.h"
#include "render_helpers.h"

namespace ps::test {

inline double pbrtReferenceLuminance(Spectrum c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Our block means of luminance (16 renders of `spp`) against pbrt-v4's render of the same
// scene file in tests/data/pbrt-v4, with no allowance: every block within 4 sigma, and the
// image's mean luminance within 4 sigma with sigma under 0.5%. Texture, lens, measured-BSDF and
// medium (../media/) paths in the file are relative to it.
// `allowance` (relative, 0 by default) widens each block's and the image's test where the two
// renderers are known to differ slightly (the caller says why). `spectral`: rendered with
// --color spectral, and the image's mean R, G and B each compared too (within 4 sigma).
inline void expectPbrtReference(const std::string& sceneFile, const std::string& refFile, int refSpp, int spp,
                                double allowance = 0, bool spectral = false) {
    const std::filesystem::path dir = std::filesystem::path(PATHSPACE_SOURCE_DIR) / "tests" / "data" / "pbrt-v4";
    std::ifstream in(dir / sceneFile);
    std::stringstream text;
    text << in.rdbuf();
    std::string scene = text.str();
    for (const std::string rel : {"\"textures/", "\"../lenses/", "\"measured/", "\"../media/"})
        for (size_t at = 0; (at = scene.find(rel, at)) != std::string::npos; at += dir.string().size() + rel.size())
            scene.insert(at + 1, dir.string() + "/");
    Image ref = readImage((dir / refFile).string());
    const int renders = 16, blocks = 4;
    BlockMeans ours = blockMeans(scene, "", spp, renders, blocks, 100, spectral);
    ASSERT_EQ(ref.width, 64);
    const int bw = ref.width / blocks, bh = ref.height / blocks;
    // The reference's noise, from ours: a render's spread scaled to the reference's samples
    // (pbrt-v4's path tracer samples these paths as ours does).
    const double refScale = std::sqrt(double(renders) * spp / refSpp);
    double refImage = 0;
    int outside = 0;
    for (int by = 0; by < blocks; ++by)
        for (int bx = 0; bx < blocks; ++bx) {
            double r = 0;
            for (int y = by * bh; y < (by + 1) * bh; ++y)
                for (int x = bx * bw; x < (bx + 1) * bw; ++x) r += pbrtReferenceLuminance(ref.get(x, y)) / (bw * bh);
            refImage += r / (blocks * blocks);
            const size_t i = size_t(by) * blocks + bx;
            // pbrt-v4 samples wavelengths, so even blocks we render without noise (the bare sky)
            // scatter in its image, by about 1e-4 relative: a floor of 2.5e-4 (4 sigma = 0.1%).
            const double se = std::hypot(ours.stdErr[i] * std::hypot(1.0, refScale), 2.5e-4 * r);
            const double z = (ours.mean[i] - r) / se;
            std::printf("  block (%d,%d): ours %.5f pbrt-v4 %.5f (%+.2f%%, %+.2f sigma)\n", bx, by, ours.mean[i], r,
                        100 * (ours.mean[i] / r - 1), z);
            if (std::fabs(ours.mean[i] - r) > 4 * se + allowance * r) ++outside;
        }
    EXPECT_EQ(outside, 0);
    const double se = ours.imageStdErr * std::hypot(1.0, refScale);
    std::printf("  image: ours %.5f pbrt-v4 %.5f, ratio %.4f +- %.4f (%+.2f sigma)\n", ours.imageMean, refImage,
                ours.imageMean / refImage, se / refImage, (ours.imageMean - refImage) / se);
    EXPECT_LT(se / refImage, 0.005) << "too noisy to detect a 2% change";
    EXPECT_NEAR(ours.imageMean, refImage, 4 * se + allowance * refImage);
    for (int c = 0; spectral && c < 3; ++c) {
        double r = 0;
        for (int y = 0; y < ref.height; ++y)
            for (int x = 0; x < ref.width; ++x) r += ref.get(x, y)[c] / (double(ref.width) * ref.height);
        const double seC = ours.channelStdErr[c] * std::hypot(1.0, refScale);
        std::printf("  channel %d: ours %.5f pbrt-v4 %.5f, ratio %.4f +- %.4f (%+.2f sigma)\n", c, ours.channelMean[c], r,
                    ours.channelMean[c] / r, seC / r, (ours.channelMean[c] - r) / seC);
        EXPECT_NEAR(ours.channelMean[c], r, 4 * seC + allowance * r) << "channel " << c;
    }
}

}  // namespace ps::test
