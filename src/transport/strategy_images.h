// Per-strategy images of BDPT (thesis fig. 10.3): for every (s, t) up to a path depth, the
// contribution of that strategy alone, weighted by its MIS weight and unweighted. Each
// unweighted image estimates the whole image of paths of its depth (when the strategy can
// sample them all); the weighted ones sum to the BDPT image. Users debug scenes with them.
// Through a thin lens the t = 0 strategies (light subpaths that reach the lens, thesis §10.2)
// have images too, splatted as the t = 1 ones are.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>
#include "film/film.h"
#include "film/filter.h"
#include "image/image.h"
#include "math/spectrum.h"

namespace ps {

class StrategyImages {
public:
    // Throws InputError if the buffers would exceed the memory limit (util/memory_limit.h).
    // `lensStrategy`: also the t = 0 strategies' images (BDPTIntegrator::lensHits).
    StrategyImages(PixelBounds bounds, int xRes, int yRes, const Filter& filter, int maxDepth, float imagingRatio,
                   bool lensStrategy = false);
    // Bytes at the peak, for images of `pixels` pixels up to maxDepth: the per-strategy sums,
    // the splat films of the t = 1 (and t = 0) strategies (splatted by `threads` threads) and
    // the output images.
    static double estimateBytes(double pixels, int maxDepth, int threads, bool lensStrategy = false);
    int maxDepth() const { return maxDepth_; }
    // Slots index strategies (s, t >= 2); -1 for strategies not recorded.
    int slotCount() const { return int(strategies_.size()); }
    int slot(int s, int t) const;
    // One camera sample's contributions, [slot * 2 + 0] weighted and [slot * 2 + 1]
    // unweighted. Pixels are owned by one thread at a time (tiles), as for the film.
    void addCameraSample(int px, int py, float filterWeight, const Spectrum* contributions);
    // Light-tracing strategies (t = 1) land anywhere; thread-safe.
    void splat(int s, Vec2 pRaster, Spectrum weighted, Spectrum unweighted, int sampleIndex);
    // The t = 0 strategy (s, 0), s >= 3, likewise; ignored without lensStrategy.
    void splatLens(int s, Vec2 pRaster, Spectrum weighted, Spectrum unweighted, int sampleIndex);
    // Over several processes (render/distributed.h): every process's sums added into rank
    // 0's (exact: fixed point), as the film's are; every process calls it.
    void sumToRoot();
    // Images named "s<S>_t<T>" and "s<S>_t<T>_unweighted" (T = 0 with lensStrategy).
    std::vector<std::pair<std::string, Image>> images(double lightPaths) const;

private:
    PixelBounds bounds_;
    int maxDepth_;
    float imagingRatio_;
    std::vector<std::pair<int, int>> strategies_;  // (s, t) by slot
    // In the film's fixed point (Film::toFixed): exact, so the images do not depend on the
    // order of the samples, the threads or the processes that took them.
    std::vector<Fixed> sums_;     // [slot][weighted/unweighted][pixel][rgb]
    std::vector<Fixed> weights_;  // per pixel: sum of filter weights of camera samples
    std::vector<std::unique_ptr<Film>> splatFilms_;  // per depth: (s = depth + 1, t = 1) weighted, unweighted
    // lensStrategy: per depth from 1: (s = depth + 2, t = 0) weighted, unweighted.
    std::vector<std::unique_ptr<Film>> lensFilms_;
};

}  // namespace ps
