// Two-stage MLT (Hoberock and Hart 2010, "arbitrary importance functions"): the chains'
// target is the path's luminance divided by a pilot image's brightness where the path lands,
// f*(x) = f(x) / B(pixel of x). Plain MLT spends its mutations in proportion to brightness,
// so a pixel's relative error grows as it darkens; with f* every tile of the image gets about
// as many mutations, and the relative error is even over the image.
//
// Unbiased whatever B is, as long as B > 0 wherever f > 0: b is estimated as the integral of
// f* by the same bootstrap, each splat is divided by f* instead of f, and the image is b*
// over the mutations as before. B comes from pilot samples of their own (bootstrap samples
// past the bootstrap's index range), so b's estimate does not depend on it.
//
// A black level L0 makes the divisor sqrt(B^2 + L0^2): relative error where the image is
// brighter than L0, absolute error where it is darker. That is the target that minimises the
// relative MSE with a regulariser, sum (x - ref)^2 / (ref^2 + L0^2): with n_j of the N
// mutations in pixel j, its variance goes as I_j^2 / n_j, and at n_j ~ I_j / w_j the error
// (sum_j I_j w_j / (I_j^2 + L0^2)) (sum_j I_j / w_j) / N is least (Cauchy-Schwarz) for
// w_j ~ sqrt(I_j^2 + L0^2). L0 = 0 is Hoberock and Hart's target; large L0 the plain one.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include <tbb/task_arena.h>

#include "film/film.h"
#include "math/vec.h"
#include "util/byte_stream.h"

namespace ps {

class PilotImportance {
public:
    // A grid of square tiles over the pixel bounds, each of about `samplesPerTile` of the
    // pilot's `pilotSamples`. `blackLevel`: L0 above, in pixel luminance (a pixel's value is
    // its samples' mean luminance over their density times the imaging ratio).
    PilotImportance(const PixelBounds& bounds, int64_t pilotSamples, double blackLevel = 0, double imagingRatio = 1,
                    double samplesPerTile = 400);
    int tiles() const { return nx_ * ny_; }
    // The tile a film position falls in (positions past the bounds: the nearest tile).
    int tileOf(Vec2 pRaster) const;
    // From the pilot's luminance per tile (its sum of f / p): each tile's mean per pixel,
    // raised to at least `floorFraction` of the image's mean (a tile the pilot found dark or
    // empty may still hold light; the floor bounds how much more often the chains visit it),
    // then combined with the black level.
    void finish(const std::vector<double>& luminanceSums, double floorFraction = 0.1);
    // Makes the map from `count` pilot samples: sample(j, sums) adds sample j's luminance over
    // its density to sums[tileOf(its film position)]. The samples run in a fixed number of
    // blocks over the arena's threads and the processes' blocks (chain_ranks.h), summed in
    // order: the same map for any thread or process count. Then finish. A cancellation (Ctrl-C)
    // skips the samples left (the bootstrap after it stops too, and the image is black).
    void learn(tbb::task_arena& arena, int64_t count, const std::function<void(int64_t, double*)>& sample,
               const std::atomic<bool>* cancel = nullptr);
    // The map and its tiles (their size follows the pilot's samples, which a time budget may
    // have cut: startup_budget.h), for a checkpoint, and back (a resumed render makes no pilot).
    void save(ByteWriter& out) const {
        out.put(int32_t(tile_));
        out.putVector(brightness_);
    }
    void load(ByteReader& in);
    // B at a film position (1 before finish).
    double at(Vec2 pRaster) const { return brightness_.empty() ? 1.0 : brightness_[size_t(tileOf(pRaster))]; }
    int tileSize() const { return tile_; }

private:
    PixelBounds bounds_;
    int tile_ = 1, nx_ = 1, ny_ = 1;
    double blackLevel_ = 0;  // in the sums' unit per pixel
    std::vector<double> brightness_;
};

}  // namespace ps
