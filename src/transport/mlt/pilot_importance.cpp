#include "transport/mlt/pilot_importance.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "render/distributed.h"
#include "transport/mlt/chain_ranks.h"

namespace ps {

PilotImportance::PilotImportance(const PixelBounds& bounds, int64_t pilotSamples, double blackLevel,
                                 double imagingRatio, double samplesPerTile)
    : bounds_(bounds) {
    const double area = double(std::max(1LL, bounds.area()));
    const double perPixel = double(std::max<int64_t>(1, pilotSamples)) / area;
    // A pixel's sums add up perPixel samples' luminance.
    blackLevel_ = imagingRatio > 0 ? std::max(0.0, blackLevel) / imagingRatio * perPixel : 0.0;
    tile_ = std::max(1, int(std::ceil(std::sqrt(samplesPerTile / perPixel))));
    nx_ = std::max(1, (bounds.width() + tile_ - 1) / tile_);
    ny_ = std::max(1, (bounds.height() + tile_ - 1) / tile_);
}

int PilotImportance::tileOf(Vec2 p) const {
    const int tx = std::clamp(int(std::floor((p.x - float(bounds_.x0)) / float(tile_))), 0, nx_ - 1);
    const int ty = std::clamp(int(std::floor((p.y - float(bounds_.y0)) / float(tile_))), 0, ny_ - 1);
    return ty * nx_ + tx;
}

void PilotImportance::finish(const std::vector<double>& sums, double floorFraction) {
    brightness_.assign(size_t(tiles()), 0.0);
    double total = 0, pixels = 0;
    for (int ty = 0; ty < ny_; ++ty)
        for (int tx = 0; tx < nx_; ++tx) {
            // Edge tiles cover fewer pixels.
            const int w = std::min(tile_, bounds_.width() - tx * tile_), h = std::min(tile_, bounds_.height() - ty * tile_);
            const double n = double(std::max(1, w * h));
            const size_t i = size_t(ty * nx_ + tx);
            const double s = i < sums.size() && std::isfinite(sums[i]) ? std::max(0.0, sums[i]) : 0.0;
            brightness_[i] = s / n;
            total += s;
            pixels += n;
        }
    const double mean = total / pixels;
    // No light found at all: every tile alike (the plain target).
    const double floor = mean > 0 ? floorFraction * mean : 1.0;
    for (double& b : brightness_) b = std::hypot(std::max(b, floor), blackLevel_);
}

void PilotImportance::learn(tbb::task_arena& arena, int64_t count, const std::function<void(int64_t, double*)>& sample,
                            const std::atomic<bool>* cancel) {
    if (count <= 0) return;
    constexpr int64_t kBlocks = 64;
    const size_t n = size_t(tiles());
    std::vector<double> blockSums(size_t(kBlocks) * n, 0.0);
    // Before finish, B is 1: the samples' target is the luminance itself.
    arena.execute([&] {
        tbb::parallel_for(int64_t(0), kBlocks, [&](int64_t block) {
            if (!chain_ranks::ownsBlock(block)) return;
            for (int64_t j = block * count / kBlocks; j < (block + 1) * count / kBlocks; ++j) {
                if (cancel && cancel->load(std::memory_order_relaxed)) return;
                sample(j, &blockSums[size_t(block) * n]);
            }
        });
    });
    {
        distributed::Purpose purpose("pilot merge");
        distributed::mergeDisjoint(blockSums);
    }
    std::vector<double> sums(n, 0.0);
    for (int64_t block = 0; block < kBlocks; ++block)
        for (size_t t = 0; t < n; ++t) sums[t] += blockSums[size_t(block) * n + t];
    finish(sums);
}

void PilotImportance::load(ByteReader& in) {
    tile_ = in.get<int32_t>();
    if (tile_ < 1) in.fail();
    nx_ = std::max(1, (bounds_.width() + tile_ - 1) / tile_);
    ny_ = std::max(1, (bounds_.height() + tile_ - 1) / tile_);
    brightness_ = in.getVector<double>();
    if (!brightness_.empty() && brightness_.size() != size_t(tiles())) in.fail();
}

}  // namespace ps
