#include "film/film.h"

#include <cmath>
#include <climits>
#include <cstring>
#include <stdexcept>

#include <tbb/task_arena.h>

#include "mc/rng.h"

namespace ps {

Film::Film(int xRes, int yRes, PixelBounds bounds, const Filter* splatFilter, bool moments)
    : xRes_(xRes), yRes_(yRes), bounds_(bounds), pixels_(size_t(bounds.area())),
      moments_(moments ? size_t(bounds.area()) : 0), high_(size_t(bounds.area())),
      halves_(splatFilter && moments ? size_t(bounds.area()) : 0), splatFilter_(splatFilter) {
    static std::atomic<uint64_t> nextId{1};
    id_ = nextId.fetch_add(1, std::memory_order_relaxed);
    if (splatFilter_) {
        splatUnitsPerWeight_ = kSplatFixedPoint / double(splatFilter_->integral());
        size_t n = size_t(bounds.area()) * 6;
        perThreadSplats_ = perThreadSplatsFit(double(bounds.area()), tbb::this_task_arena::max_concurrency());
        if (!perThreadSplats_) {
            splats_.reset(new std::atomic<int64_t>[n]);
            for (size_t i = 0; i < n; ++i) splats_[i].store(0, std::memory_order_relaxed);
        }
    }
}

void Film::setMaxComponentValue(float m, float imagingRatio, const ClampSpace& sensorFromL) {
    maxComponent_ = m;
    clampSpace_ = sensorFromL;
    splatMaxComponent_ = std::numeric_limits<float>::infinity();
    if (splatFilter_ && imagingRatio > 0 && std::isfinite(m))
        splatMaxComponent_ = float(double(m) * double(bounds_.area()) / (splatPixelCount() * imagingRatio));
}

void Film::setChainMaxComponentValue(float m, float imagingRatio, const ClampSpace& sensorFromL) {
    setMaxComponentValue(m, imagingRatio, sensorFromL);
    // A chain's splat is clamped as it is given, not as the camera sample it stands for.
    if (splatFilter_ && imagingRatio > 0 && std::isfinite(m)) splatMaxComponent_ = m / imagingRatio;
}

bool Film::perThreadSplatsFit(double pixels, int threads) {
    return kSplatBytesPerPixel * pixels * threads < kPerThreadSplatBytes;
}

double Film::estimateBytes(double pixels, bool splats, int threads, bool moments) {
    double perPixel = sizeof(Pixel) + 2 * 3 * sizeof(float) + sizeof(int);  // accumulators, two images, counts
    if (moments) perPixel += sizeof(Moments) + (splats ? sizeof(Halves) : 0);
    if (splats) {
        const double copies = perThreadSplatsFit(pixels, threads) ? threads : 1;
        perPixel += kSplatBytesPerPixel * (copies + 1);  // + the merged copy
    }
    return perPixel * pixels;
}

std::vector<int64_t> Film::mergedSplats() const {
    size_t n = splatFilter_ ? size_t(bounds_.area()) * 6 : 0;
    std::vector<int64_t> merged(n, 0);
    if (!perThreadSplats_) {
        for (size_t i = 0; i < n; ++i) merged[i] = splats_[i].load(std::memory_order_relaxed);
        return merged;
    }
    for (const std::vector<int64_t>& t : threadSplats_)
        for (size_t i = 0; i < t.size(); ++i) merged[i] += t[i];
    return merged;
}

int64_t* Film::threadSplatSums() {
    // The thread's own sums, found once per thread and film: a TBB thread-specific lookup
    // per splat costs about as much as the splat. Films get unique ids, so an entry left by
    // a destroyed film is never taken for a new one at the same address.
    thread_local struct {
        uint64_t film = 0;
        int64_t* sums = nullptr;
    } cache;
    if (cache.film != id_) {
        std::vector<int64_t>& local = threadSplats_.local();
        if (local.empty()) local.assign(size_t(bounds_.area()) * 6, 0);
        cache = {id_, local.data()};
    }
    return cache.sums;
}

Film::PixelRange Film::splatFootprint(Vec2 pFilm) const {
    Vec2 r = splatFilter_->radius();
    int x0 = std::max(bounds_.x0, int(std::ceil(pFilm.x - 0.5f - r.x)));
    int x1 = std::min(bounds_.x1 - 1, int(std::floor(pFilm.x - 0.5f + r.x)));
    int y0 = std::max(bounds_.y0, int(std::ceil(pFilm.y - 0.5f - r.y)));
    int y1 = std::min(bounds_.y1 - 1, int(std::floor(pFilm.y - 0.5f + r.y)));
    return {x0, x1, y0, y1};
}

void Film::prefetchSplat(Vec2 pFilm, int sampleIndex) {
    if (!splatFilter_) return;
    const auto [x0, x1, y0, y1] = splatFootprint(pFilm);
    if (x0 > x1 || y0 > y1) return;
    const char* sums = perThreadSplats_ ? reinterpret_cast<const char*>(threadSplatSums())
                                        : reinterpret_cast<const char*>(splats_.get());
    for (int y = y0; y <= y1; ++y) {
        const char* first = sums + splatOffset(index(x0, y), sampleIndex & 1) * sizeof(int64_t);
        const char* last = sums + (splatOffset(index(x1, y), sampleIndex & 1) + 3) * sizeof(int64_t) - 1;
        for (const char* a = first; a < last; a += 64) __builtin_prefetch(a, 1);
        __builtin_prefetch(last, 1);
    }
}

void Film::addSplat(Vec2 pFilm, Spectrum L, int sampleIndex) {
    if (!splatFilter_) return;
    if (!L.isFinite()) {
        rejected_.fetch_add(1, std::memory_order_relaxed);
        return;
    }
    if (L.isBlack()) return;
    L = clampMaxComponent(L, splatMaxComponent_, clampSpace_);
    // Every pixel whose filter footprint covers pFilm gets its filter-weighted share.
    const auto [x0, x1, y0, y1] = splatFootprint(pFilm);
    int64_t* local = perThreadSplats_ ? threadSplatSums() : nullptr;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            float w = splatFilter_->evaluate({pFilm.x - (x + 0.5f), pFilm.y - (y + 0.5f)});
            if (w == 0) continue;
            size_t base = splatOffset(index(x, y), sampleIndex & 1);
            const double units = double(w) * splatUnitsPerWeight_;
            double v[3] = {double(L[0]) * units, double(L[1]) * units, double(L[2]) * units};
            if (!(std::fabs(v[0]) < 0x1p60 && std::fabs(v[1]) < 0x1p60 && std::fabs(v[2]) < 0x1p60)) {
                rejected_.fetch_add(1, std::memory_order_relaxed);  // would overflow the accumulator
                continue;
            }
            // Dithered rounding keeps the fixed-point sum unbiased; the dither is a hash of
            // the value itself (21 bits per channel), so it does not depend on the thread schedule.
            uint64_t bits;
            std::memcpy(&bits, &v[0], sizeof bits);
            uint64_t h = mix64(bits ^ (uint64_t(base) << 40) ^ uint64_t(std::fabs(v[1]) + std::fabs(v[2])));
            for (int c = 0; c < 3; ++c) {
                double dither = double((h >> (21 * c)) & 0x1fffff) * 0x1p-21;
                int64_t q = int64_t(std::floor(v[c] + dither));
                if (q == 0) continue;
                if (local) local[base + c] += q;
                else splats_[base + c].fetch_add(q, std::memory_order_relaxed);
            }
        }
}

Image Film::image(double lightPaths) const {
    const double splatScale = splatFilter_ && lightPaths > 0 ? splatPixelCount() / lightPaths : 0.0;
    const std::vector<int64_t> splats = mergedSplats();
    Image img(bounds_.width(), bounds_.height());
    for (int y = 0; y < bounds_.height(); ++y)
        for (int x = 0; x < bounds_.width(); ++x) {
            const size_t i = size_t(y) * bounds_.width() + x;
            const Pixel& p = pixels_[i];
            Spectrum v;
            if (const int64_t* h = high_.find(i)) {  // some sum of the pixel's block went past 64 bits
                const double w = double(wideSum(p.weight, h[3]));
                if (w != 0)
                    v = Spectrum(float(double(wideSum(p.sum[0], h[0])) / w), float(double(wideSum(p.sum[1], h[1])) / w),
                                 float(double(wideSum(p.sum[2], h[2])) / w));
            } else if (p.weight != 0) {  // the same arithmetic on the same integers, in 64 bits
                const double w = double(p.weight);
                v = Spectrum(float(double(p.sum[0]) / w), float(double(p.sum[1]) / w), float(double(p.sum[2]) / w));
            }
            if (splatScale > 0) {
                size_t i = size_t(y) * bounds_.width() + x;
                for (int c = 0; c < 3; ++c)
                    v[c] += float((splatValue(splats, i, 0, c) + splatValue(splats, i, 1, c)) * splatScale);
            }
            if (!v.isFinite()) v = Spectrum();
            img.set(x, y, v);
        }
    return img;
}

Film::PixelEstimate Film::pixelEstimate(size_t i) const {
    const Pixel& p = pixels_[i];
    PixelEstimate e;
    e.samples = p.samples;
    if (p.samples == 0 || moments_.empty()) return e;
    double n = double(p.samples);
    e.mean = double(pixelSum(i, 4)) / kSumUnit / n;
    if (p.samples > 1)
        e.sampleVariance = std::max(0.0, (double(pixelSum(i, 5)) / kFixedSquareUnit - n * e.mean * e.mean) / (n - 1));
    return e;
}

double Film::pixelVariance(size_t i, double lightPaths, const std::vector<int64_t>& splats, double& mean) const {
    mean = 0;
    if (moments_.empty()) return 0;  // nothing to estimate from
    if (!splatFilter_) {
        PixelEstimate e = pixelEstimate(i);
        mean = e.mean;
        return e.varianceOfMean();
    }
    // Two independent half estimates H0, H1 of the pixel: Var((H0+H1)/2) ~ (H0-H1)^2/4.
    const double halfScale = lightPaths > 0 ? 2 * splatPixelCount() / lightPaths : 0.0;
    double h[2];
    for (int k = 0; k < 2; ++k) {
        const Halves& hp = halves_[i];
        h[k] = hp.weight[k] != 0 ? fromFixed(hp.y[k]) / fromFixed(hp.weight[k]) : 0.0;
        Spectrum s(float(splatValue(splats, i, k, 0)), float(splatValue(splats, i, k, 1)),
                   float(splatValue(splats, i, k, 2)));
        h[k] += s.luminance() * halfScale;
    }
    mean = 0.5 * (h[0] + h[1]);
    return 0.25 * (h[0] - h[1]) * (h[0] - h[1]);
}

Film::ErrorEstimate Film::errorEstimate(double lightPaths) const {
    ErrorEstimate e;
    if (pixels_.empty() || moments_.empty()) return e;
    const std::vector<int64_t> splats = mergedSplats();
    for (size_t i = 0; i < pixels_.size(); ++i) {
        double m = 0;
        double v = pixelVariance(i, lightPaths, splats, m);
        e.meanVariance += v;
        e.meanRelativeVariance += v / (m * m + kRelativeEpsilon);
    }
    e.meanVariance /= double(pixels_.size());
    e.meanRelativeVariance /= double(pixels_.size());
    return e;
}

Image Film::varianceImage(double lightPaths) const {
    Image img(bounds_.width(), bounds_.height());
    const std::vector<int64_t> splats = mergedSplats();
    for (int y = 0; y < bounds_.height(); ++y)
        for (int x = 0; x < bounds_.width(); ++x) {
            double m = 0;
            float v = float(pixelVariance(size_t(y) * bounds_.width() + x, lightPaths, splats, m));
            img.set(x, y, std::isfinite(v) ? Spectrum(v, v, v) : Spectrum());
        }
    return img;
}

std::vector<int> Film::sampleCounts() const {
    std::vector<int> n(pixels_.size());
    for (size_t i = 0; i < pixels_.size(); ++i) n[i] = int(std::min<long long>(pixels_[i].samples, INT_MAX));
    return n;
}

void Film::adoptEmptyPixels(const Film& other) {
    for (size_t i = 0; i < pixels_.size() && i < other.pixels_.size(); ++i) {
        if (pixels_[i].samples != 0) continue;
        pixels_[i] = other.pixels_[i];
        if (!moments_.empty()) moments_[i] = other.moments_.empty() ? Moments{} : other.moments_[i];
        if (const int64_t* h = other.high_.find(i)) std::copy(h, h + kWideSums, high_.at(i));
        else if (high_.find(i)) std::fill(high_.at(i), high_.at(i) + kWideSums, 0);
    }
}

double Film::meanSamplesPerPixel() const {
    long double total = 0;
    for (const Pixel& p : pixels_) total += p.samples;
    return pixels_.empty() ? 0.0 : double(total / pixels_.size());
}

Film::Accumulators Film::accumulators() const {
    Accumulators a;
    a.fixed.resize(pixels_.size() * kFixedPerPixel);
    a.counts.resize(pixels_.size());
    pixelSums(0, pixels_.size(), a.fixed.data(), a.counts.data());
    const std::vector<int64_t> other = otherCounts();
    a.counts.insert(a.counts.end(), other.begin(), other.end());
    return a;
}

void Film::setAccumulators(const Accumulators& a) {
    const size_t splatCount = splatFilter_ ? size_t(bounds_.area()) * 6 : 0;
    if (a.fixed.size() != pixels_.size() * kFixedPerPixel || a.counts.size() != pixels_.size() + splatCount + 1)
        throw std::logic_error("Film::setAccumulators: sums of another film's size");
    setPixelSums(0, pixels_.size(), a.fixed.data(), a.counts.data());
    setOtherCounts(std::vector<int64_t>(a.counts.begin() + std::ptrdiff_t(pixels_.size()), a.counts.end()));
}

Fixed Film::pixelSum(size_t i, int k) const {
    const Pixel& p = pixels_[i];
    const int64_t low = k < 3 ? p.sum[k] : k == 3 ? p.weight : moments_.empty() ? 0 : k == 4 ? moments_[i].y : moments_[i].y2;
    return wideSum(low, high_.word(i, k));
}

void Film::pixelSums(size_t begin, size_t end, Fixed* fixed, int64_t* counts) const {
    for (size_t i = begin; i < end; ++i, fixed += kFixedPerPixel) {
        const Halves h = halves_.empty() ? Halves() : halves_[i];
        for (int k = 0; k < kWideSums; ++k) fixed[k] = pixelSum(i, k);
        const Fixed f[4] = {h.y[0], h.y[1], h.weight[0], h.weight[1]};
        std::copy(f, f + 4, fixed + kWideSums);
        *counts++ = pixels_[i].samples;
    }
}

void Film::setPixelSums(size_t begin, size_t end, const Fixed* f, const int64_t* counts) {
    for (size_t i = begin; i < end; ++i, f += kFixedPerPixel) {
        Pixel& p = pixels_[i];
        int64_t low[kWideSums], high[kWideSums];
        bool wide = false;
        for (int k = 0; k < kWideSums; ++k) {
            splitSum(f[k], low[k], high[k]);
            wide = wide || high[k] != 0;
        }
        p.sum[0] = low[0], p.sum[1] = low[1], p.sum[2] = low[2], p.weight = low[3];
        if (!moments_.empty()) moments_[i] = {low[4], low[5]};
        if (wide || high_.find(i)) std::copy(high, high + kWideSums, high_.at(i));
        if (!halves_.empty()) {
            Halves& h = halves_[i];
            h.y[0] = f[6], h.y[1] = f[7], h.weight[0] = f[8], h.weight[1] = f[9];
        }
        p.samples = *counts++;
    }
}

std::vector<int64_t> Film::otherCounts() const {
    std::vector<int64_t> c = mergedSplats();
    c.push_back(rejected_.load());
    return c;
}

void Film::setOtherCounts(const std::vector<int64_t>& c) {
    const size_t splatCount = splatFilter_ ? size_t(bounds_.area()) * 6 : 0;
    if (c.size() != splatCount + 1) throw std::logic_error("Film::setOtherCounts: counts of another film's size");
    if (splatFilter_) {
        // The sums now live in one shared array: the per-thread copies are dropped.
        perThreadSplats_ = false;
        threadSplats_.clear();
        splats_.reset(new std::atomic<int64_t>[splatCount]);
        for (size_t i = 0; i < splatCount; ++i) splats_[i].store(c[i], std::memory_order_relaxed);
    }
    rejected_.store(c.back());
}

}  // namespace ps
