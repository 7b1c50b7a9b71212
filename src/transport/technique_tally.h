// Figures per sampling technique (`--stats`; docs/strategy-figures.md): each technique's
// share of the image, the variance of its contribution to the image mean, and its
// efficiency. A technique is a BDPT strategy (s, t) or one of the path tracer's two (light
// sampling, BSDF sampling), MIS-weighted as they enter the image (thesis ch. 9: the weighted
// techniques sum to the image, so their shares sum to one).
//
// Each camera sample j (with the light subpath and splats it makes) is one sample of
//   Y_kj = its technique k's contribution to the image's mean luminance,
// and technique k's figure of the image is M_k = mean_j Y_kj. The variance reported is that
// of M_k: from the samples' own spread, s^2 / N, when they are independent, and from the
// spread of the means of K independently scrambled sample sets when they are not (stratified
// and QMC samplers: s^2 / N ignores their gain, thesis §2.6; Owen's replicates).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "math/spectrum.h"
#include "math/vec.h"

namespace ps {

// What an integrator tells of its techniques (Integrator::techniques).
struct RenderTechnique {
    std::string name;   // "light", "bsdf", or "s2_t3"
    int s = -1, t = -1;  // BDPT's strategy; -1 for the path tracer's
    bool splat = false;  // lands anywhere on the film (light tracing's t <= 1), not on its own pixel
    bool possible = true;  // false: a slot of the index that no sample fills (BDPT's (1, 1))
};

// One thread's sums; the integrators add a sample's contributions, the sample loop closes it.
class TechniqueTally {
public:
    TechniqueTally() = default;
    // `sets`: independent sample sets (1: the samples are independent themselves); splats
    // count where they land in the raster region [x0, x1) x [y0, y1) (the crop's pixels).
    TechniqueTally(int techniques, int sets, Vec2 lo, Vec2 hi);
    bool empty() const { return current_.empty(); }
    // A contribution (the film's RGB) of technique k to this camera sample: on its own pixel
    // (before the filter and camera weights) or splatted at pRaster.
    void addCamera(int k, const Spectrum& L) {
        if (L.isFinite()) current_[size_t(k)] += double(L.luminance());
    }
    void addSplat(int k, const Spectrum& L, Vec2 pRaster) {
        if (L.isFinite() && pRaster.x >= lo_.x && pRaster.x < hi_.x && pRaster.y >= lo_.y && pRaster.y < hi_.y)
            splatCurrent_[size_t(k)] += double(L.luminance());
    }
    // Closes the sample of set `set`: camera contributions scaled by `cameraScale` (filter
    // weight, camera weight, imaging ratio; normalised by the mean filter weight, as a pixel
    // is by its own), splats by `splatScale` (a unit splat's share of the image mean,
    // Film::image's normalisation).
    void endSample(int set, double cameraScale, double splatScale, double filterWeight);
    void merge(const TechniqueTally& o);

    // The figures, over every thread's tally merged; `seconds`: the render's time.
    struct Figure {
        double mean = 0;      // M_k: the technique's contribution to the image's mean luminance
        double share = 0;     // M_k over the sum of every technique's
        double variance = 0;  // Var(M_k)
        double relativeVariance = 0;  // Var(M_k) / M^2, M the image mean (the sum of the M_k)
        double efficiency = 0;        // 1 / (relativeVariance * seconds)
    };
    // Per technique, then one more for the whole image (the Y_kj summed over k: the
    // strategies' covariances make its variance differ from the sum of theirs).
    std::vector<Figure> figures(double seconds) const;
    long long samples() const;

private:
    // Per set, per technique and the whole (techniques_ + 1 entries): the sums of a sample's
    // camera part C and splatted part S, and of C^2, C S and S^2, so that the camera parts
    // can be divided by the mean filter weight once it is known.
    enum Moment { kC, kS, kCC, kCS, kSS, kMoments };
    double& at(int set, int k, Moment m) { return sums_[(size_t(set) * size_t(techniques_ + 1) + size_t(k)) * kMoments + m]; }
    double at(int set, int k, Moment m) const {
        return sums_[(size_t(set) * size_t(techniques_ + 1) + size_t(k)) * kMoments + m];
    }

    int techniques_ = 0, sets_ = 1;
    Vec2 lo_, hi_;
    std::vector<double> current_, splatCurrent_;  // this sample's, per technique
    std::vector<double> sums_;
    std::vector<double> weight_;    // per set: the camera samples' filter weights
    std::vector<long long> count_;  // per set
};

}  // namespace ps
