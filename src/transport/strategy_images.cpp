#include "transport/strategy_images.h"

#include <cmath>

#include <tbb/task_arena.h>

#include "render/distributed.h"
#include "transport/film_reduction.h"
#include "util/memory_limit.h"

namespace ps {

namespace {
// Strategies with t >= 2 (camera samples) up to maxDepth: depth d has d + 1 of them.
size_t cameraStrategies(int maxDepth) { return size_t(maxDepth + 1) * size_t(maxDepth + 2) / 2; }
// Strategies with t = 0 (a thin lens) up to maxDepth: one at each depth from 1 (s >= 3).
size_t lensStrategies(int maxDepth, bool lens) { return lens ? size_t(maxDepth) : 0; }
// Output images: each camera strategy, each t = 1 strategy (s >= 2) and each t = 0 strategy,
// weighted and unweighted.
size_t outputImages(int maxDepth, bool lens) {
    return 2 * (cameraStrategies(maxDepth) + size_t(maxDepth) + lensStrategies(maxDepth, lens));
}
}  // namespace

double StrategyImages::estimateBytes(double pixels, int maxDepth, int threads, bool lensStrategy) {
    const double sums = double(cameraStrategies(maxDepth)) * 2 * 3 * sizeof(Fixed) + sizeof(Fixed);  // + weights_
    const double images = double(outputImages(maxDepth, lensStrategy)) * 3 * sizeof(float);
    const double splatFilms = 2.0 * (maxDepth + 1) + 2.0 * double(lensStrategies(maxDepth, lensStrategy));
    return pixels * (sums + images) + splatFilms * Film::estimateBytes(pixels, true, threads);
}

StrategyImages::StrategyImages(PixelBounds bounds, int xRes, int yRes, const Filter& filter, int maxDepth,
                               float imagingRatio, bool lensStrategy)
    : bounds_(bounds), maxDepth_(maxDepth), imagingRatio_(imagingRatio) {
    // The splat films decide on per-thread copies with the same concurrency (see Film's constructor).
    requireMemory("--bdpt-strategies (" + std::to_string(outputImages(maxDepth, lensStrategy)) + " strategy images of " +
                      std::to_string(bounds.width()) + "x" + std::to_string(bounds.height()) + ")",
                  estimateBytes(double(bounds.area()), maxDepth, tbb::this_task_arena::max_concurrency(), lensStrategy));
    for (int depth = 0; depth <= maxDepth; ++depth)
        for (int t = 2; t <= depth + 2; ++t) strategies_.push_back({depth + 2 - t, t});
    sums_.assign(strategies_.size() * 2 * size_t(bounds.area()) * 3, 0);
    weights_.assign(size_t(bounds.area()), 0);
    for (int depth = 0; depth <= maxDepth; ++depth)
        for (int k = 0; k < 2; ++k) splatFilms_.push_back(std::make_unique<Film>(xRes, yRes, bounds, &filter));
    for (size_t i = 0; i < 2 * lensStrategies(maxDepth, lensStrategy); ++i)
        lensFilms_.push_back(std::make_unique<Film>(xRes, yRes, bounds, &filter));
}

int StrategyImages::slot(int s, int t) const {
    int depth = s + t - 2;
    if (t < 2 || depth < 0 || depth > maxDepth_) return -1;
    // Depth d occupies d + 1 slots (t = 2 .. d + 2) after those of smaller depths.
    return depth * (depth + 1) / 2 + (t - 2);
}

void StrategyImages::addCameraSample(int px, int py, float filterWeight, const Spectrum* contributions) {
    size_t pixel = size_t(py - bounds_.y0) * bounds_.width() + (px - bounds_.x0);
    weights_[pixel] += Film::toFixed(filterWeight);
    size_t area = size_t(bounds_.area());
    for (size_t i = 0; i < strategies_.size() * 2; ++i) {
        const Spectrum& c = contributions[i];
        if (c.isBlack() || !c.isFinite()) continue;
        Fixed* p = &sums_[(i * area + pixel) * 3];
        for (int ch = 0; ch < 3; ++ch) {
            const double v = double(c[ch]) * filterWeight * imagingRatio_;
            if (std::fabs(v) < Film::kMaxSampleValue) p[ch] += Film::toFixed(v);  // as the film rejects larger ones
        }
    }
}

void StrategyImages::splat(int s, Vec2 pRaster, Spectrum weighted, Spectrum unweighted, int sampleIndex) {
    int depth = s - 1;
    if (depth < 0 || depth > maxDepth_) return;
    splatFilms_[size_t(depth) * 2]->addSplat(pRaster, weighted, sampleIndex);
    splatFilms_[size_t(depth) * 2 + 1]->addSplat(pRaster, unweighted, sampleIndex);
}

void StrategyImages::splatLens(int s, Vec2 pRaster, Spectrum weighted, Spectrum unweighted, int sampleIndex) {
    const int depth = s - 2;
    if (lensFilms_.empty() || depth < 1 || depth > maxDepth_) return;
    lensFilms_[size_t(depth - 1) * 2]->addSplat(pRaster, weighted, sampleIndex);
    lensFilms_[size_t(depth - 1) * 2 + 1]->addSplat(pRaster, unweighted, sampleIndex);
}

void StrategyImages::sumToRoot() {
    if (distributed::size() == 1) return;
    distributed::Purpose purpose("strategy images");
    distributed::sumToRoot(sums_);
    distributed::sumToRoot(weights_);
    for (const auto& f : splatFilms_) sumFilmInto(*f, *f);
    for (const auto& f : lensFilms_) sumFilmInto(*f, *f);
}

std::vector<std::pair<std::string, Image>> StrategyImages::images(double lightPaths) const {
    std::vector<std::pair<std::string, Image>> out;
    size_t area = size_t(bounds_.area());
    // Appended piecewise: "s" + std::to_string(...) trips GCC 12's false -Wrestrict (GCC PR 105329).
    auto name = [](int s, int t, int k) {
        std::string n = "s";
        n += std::to_string(s);
        n += "_t";
        n += std::to_string(t);
        if (k) n += "_unweighted";
        return n;
    };
    for (size_t i = 0; i < strategies_.size(); ++i)
        for (int k = 0; k < 2; ++k) {
            Image img(bounds_.width(), bounds_.height());
            const Fixed* src = &sums_[((i * 2 + size_t(k)) * area) * 3];
            for (size_t p = 0; p < area; ++p)
                for (int ch = 0; ch < 3; ++ch)
                    img.rgb[p * 3 + ch] =
                        weights_[p] != 0 ? float(Film::fromFixed(src[p * 3 + ch]) / Film::fromFixed(weights_[p])) : 0.0f;
            out.push_back({name(strategies_[i].first, strategies_[i].second, k), std::move(img)});
        }
    for (int depth = 1; depth <= maxDepth_; ++depth)  // (1, 1) is not a BDPT strategy
        for (int k = 0; k < 2; ++k)
            out.push_back({name(depth + 1, 1, k), splatFilms_[size_t(depth) * 2 + size_t(k)]->image(lightPaths)});
    for (size_t i = 0; i < lensFilms_.size(); ++i)
        out.push_back({name(int(i / 2) + 3, 0, int(i % 2)), lensFilms_[i]->image(lightPaths)});
    return out;
}

}  // namespace ps
