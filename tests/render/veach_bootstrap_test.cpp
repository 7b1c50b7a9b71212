// Veach's mlt bootstrap is stratified (veach_mlt.cpp, stratifiedStart: the first numbers of
// each sample come from a PaddedStrata set over the bootstrap's samples): b, which scales the
// whole image, spreads across seeds well under what independent samples would give. The
// render reports that (its b relative error is computed as for independent samples), so the
// test needs no second estimator. Each sample stays uniform on its own: b's unbiasedness is
// checked by the closed furnace and the box against BDPT (veach_mlt_test.cpp); and every
// render here starts its chains from replayed bootstrap samples (one that differed throws).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "mc/estimator.h"
#include "mlt_scenes.h"
#include "render_helpers.h"

using namespace ps;
using namespace ps::test;

namespace {

// b's observed relative spread across `seeds` renders over the mean of the reported
// (independent-sample) relative error: about 1 for independent samples.
double spreadOverIndependent(const std::string& scene, bool spectral, int seeds) {
    RunningStats b, reported;
    for (int k = 0; k < seeds; ++k) {
        const RenderResult r = renderString(scene, 1, 500 + uint64_t(k), 0, "mlt", spectral);
        b.add(r.metropolis.b);
        reported.add(r.metropolis.bRelativeError);
    }
    const double ratio = std::sqrt(b.variance()) / b.mean() / reported.mean();
    std::printf("[ mlt ] %s: b %.5f, spread %.3f%% per render, independent samples' %.3f%%: ratio %.2f\n",
                spectral ? "spectral" : "rgb", b.mean(), 100 * std::sqrt(b.variance()) / b.mean(),
                100 * reported.mean(), ratio);
    return ratio;
}

}  // namespace

// 64 seeds estimate the ratio within about 9% of itself: independent samples (ratio 1) are
// 2.8 of those errors above the bound; the stratified bootstrap measured 0.57 in both modes
// (0.53 and 0.54 on the agreement matrix's base box at 15000 samples, 32 seeds).
TEST(VeachMLTBootstrap, BSpreadsLessThanIndependentSamplesWould) {
    const std::string scene = withBootstrap(box("6 6 6", "0.7 0.1 0.1", "0.1 0.7 0.1"), 4000);
    for (bool spectral : {false, true}) EXPECT_LT(spreadOverIndependent(scene, spectral, 64), 0.75);
}
