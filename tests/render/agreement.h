// Agreement of independent estimators (thesis ch. 10's strongest check): integrators that
// estimate the same image must agree, with the standard errors measured from the spread of
// independent renders (seeds 100, 101, ...), never from the per-sample variance.
//
// Two tests per pair of integrators:
// - pooled: the image's mean luminance must agree within 4 standard errors, and those errors
//   must be small enough that a uniform 1% difference between the integrators would fail;
// - local: each block's mean luminance within 4 standard errors plus a floor of 1% of the
//   image mean (dim blocks of heavy-tailed estimates, such as light tracing at grazing
//   angles, have standard errors that a few renders underestimate). A bias confined to part
//   of the image shows here.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "render_helpers.h"

namespace ps::test {

struct AgreementCase {
    const char* name;
    std::string scene;
    std::vector<std::string> integrators;  // the first is compared with each other one
    int spp;
    int renders = 16;
    std::map<std::string, int> sppOf = {};  // per-integrator spp where one needs more than `spp`
    double detectableBias = 0.01;           // see kDetectableBias
    // --color spectral; the image's R, G and B means are then compared too, each within 4
    // sigma, and each block's, within 4 sigma + 1% of the channel's image mean (a wrong
    // spectrum can keep the luminance and move the colour, or spread it wrongly: dispersion).
    // By default the tests' mode (render_helpers.h, defaultSpectral).
    bool spectral = defaultSpectral();
};

// The smallest uniform relative difference the pooled test must be able to detect (by
// default; a case may ask for less where an estimator's image mean is costly to pin down).
constexpr double kDetectableBias = 0.01;
constexpr int kAgreementBlocks = 4;

inline void expectAgreement(const AgreementCase& c) {
    std::vector<BlockMeans> results;
    for (const std::string& integ : c.integrators) {
        auto own = c.sppOf.find(integ);
        results.push_back(blockMeans(c.scene, integ, own == c.sppOf.end() ? c.spp : own->second, c.renders, kAgreementBlocks,
                                     100, c.spectral));
    }
    const BlockMeans& a = results[0];
    ASSERT_GT(a.imageMean, 0.01) << c.name << ": the scene must be lit";
    for (size_t k = 1; k < results.size(); ++k) {
        const BlockMeans& b = results[k];
        const char *na = c.integrators[0].c_str(), *nb = c.integrators[k].c_str();
        double seImage = std::hypot(a.imageStdErr, b.imageStdErr);
        double zImage = (b.imageMean - a.imageMean) / std::max(seImage, 1e-12);
        std::printf("  %s: %s vs %s: image %.5f +- %.5f vs %.5f +- %.5f (ratio %.4f, %.2f sigma; 4 sigma = %.2f%%)\n",
                    c.name, na, nb, a.imageMean, a.imageStdErr, b.imageMean, b.imageStdErr, b.imageMean / a.imageMean,
                    zImage, 400 * seImage / a.imageMean);
        EXPECT_LT(4 * seImage, c.detectableBias * a.imageMean)
            << c.name << ": " << nb << " too noisy to detect a " << 100 * c.detectableBias << "% bias";
        EXPECT_LT(std::fabs(zImage), 4.0) << c.name << ": " << na << " vs " << nb << " image means differ";
        for (int ch = 0; c.spectral && ch < 3; ++ch) {
            double se = std::hypot(a.channelStdErr[ch], b.channelStdErr[ch]);
            double z = (b.channelMean[ch] - a.channelMean[ch]) / std::max(se, 1e-12);
            std::printf("  %s: channel %d: %.5f +- %.5f vs %.5f +- %.5f (%.2f sigma)\n", c.name, ch, a.channelMean[ch],
                        a.channelStdErr[ch], b.channelMean[ch], b.channelStdErr[ch], z);
            EXPECT_LT(std::fabs(z), 4.0) << c.name << ": " << na << " vs " << nb << " channel " << ch << " differs";
        }

        int failures = 0;
        double worst = 0;
        for (int ch = 0; c.spectral && ch < 3; ++ch)
            for (size_t i = 0; i < a.mean.size(); ++i) {
                const double ma = a.blockChannelMean[ch][i], mb = b.blockChannelMean[ch][i];
                const double se = std::hypot(a.blockChannelStdErr[ch][i], b.blockChannelStdErr[ch][i]);
                worst = std::max(worst, std::fabs(ma - mb) / std::max(se, 1e-12));
                if (std::fabs(ma - mb) > 4 * se + 0.01 * a.channelMean[ch]) {
                    ++failures;
                    ADD_FAILURE() << c.name << ": " << na << " vs " << nb << " block " << i << " channel " << ch << ": "
                                  << ma << " +- " << a.blockChannelStdErr[ch][i] << " vs " << mb << " +- "
                                  << b.blockChannelStdErr[ch][i];
                }
            }
        for (size_t i = 0; i < a.mean.size(); ++i) {
            double se = std::hypot(a.stdErr[i], b.stdErr[i]);
            double z = std::fabs(a.mean[i] - b.mean[i]) / std::max(se, 1e-12);
            worst = std::max(worst, z);
            // The block test must be able to fail: its noise must be small against the image.
            EXPECT_LT(se, 0.03 * a.imageMean + 0.03 * a.mean[i]) << c.name << ": " << nb << " block " << i << " too noisy";
            if (std::fabs(a.mean[i] - b.mean[i]) > 4 * se + 0.01 * a.imageMean) {
                ++failures;
                ADD_FAILURE() << c.name << ": " << na << " vs " << nb << " block " << i << ": " << a.mean[i] << " +- "
                              << a.stdErr[i] << " vs " << b.mean[i] << " +- " << b.stdErr[i];
            }
        }
        std::printf("  %s: %s vs %s: largest block |diff| %.2f sigma, %d blocks beyond 4 sigma + 1%%\n", c.name, na,
                    nb, worst, failures);
    }
}

}  // namespace ps::test
