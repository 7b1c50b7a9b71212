// The film accumulates weighted camera samples per pixel (sum of w*L and of w) and counts
// what it had to reject, so no NaN or infinity ever reaches an image.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>
#include <memory>
#include <tbb/enumerable_thread_specific.h>
#include "film/exact_sum.h"
#include "film/filter.h"
#include "image/image.h"
#include "math/spectrum.h"
#include "util/zeroed_array.h"

namespace ps {

struct PixelBounds {
    int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // half-open [x0,x1) x [y0,y1) in full-resolution raster
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    long long area() const { return (long long)width() * height(); }
};

// pbrt-v4's cropwindow [x0 x1 y0 y1] in NDC (y down) -> pixels [ceil(x0 W), ceil(x1 W)) x ...
inline PixelBounds cropWindowToPixels(int xRes, int yRes, const float crop[4]) {
    auto c = [](float v) { return std::min(1.0f, std::max(0.0f, v)); };
    auto px = [](int res, float v) { return int(std::ceil(res * v)); };
    return {px(xRes, c(std::min(crop[0], crop[1]))), px(xRes, c(std::max(crop[0], crop[1]))),
            px(yRes, c(std::min(crop[2], crop[3]))), px(yRes, c(std::max(crop[2], crop[3])))};
}

// pbrt-v4's Film "maxcomponentvalue" (RGBFilm::AddSample, AddSplat): a sample whose largest
// component in the sensor's space exceeds m is scaled down so that it equals m (hue kept).
// pbrt-v4 measures the components before the sensor's output matrix, so for its default
// "cie1931" sensor they are X, Y, Z, not the image's R, G, B: `sensorFromL` takes L (the film's
// RGB) there. Biased (energy is lost), but it tames fireflies.
using ClampSpace = std::array<float, 9>;  // row-major
constexpr ClampSpace kIdentityClampSpace = {1, 0, 0, 0, 1, 0, 0, 0, 1};
inline Spectrum clampMaxComponent(Spectrum L, float m, const ClampSpace& sensorFromL) {
    if (!(m < std::numeric_limits<float>::infinity())) return L;
    const auto& a = sensorFromL;
    const float x = a[0] * L.r + a[1] * L.g + a[2] * L.b, y = a[3] * L.r + a[4] * L.g + a[5] * L.b,
                z = a[6] * L.r + a[7] * L.g + a[8] * L.b;
    const float mx = std::max(x, std::max(y, z));
    return mx > m ? L * (m / mx) : L;
}

class Film {
public:
    // With a filter the film also accepts splats (light-path contributions that land
    // anywhere on the film, thesis §10.2's t = 1 strategies); then the render error is
    // measured from two independent half-buffers (even and odd sample indices), because
    // a pixel's splats do not come from its own samples.
    // `moments`: whether the film keeps what its error estimate needs (the luminance moments,
    // and for a splatting film the half-buffers); without them errorEstimate, varianceImage
    // and pixelEstimate have nothing to estimate from (the image is the same either way).
    Film(int xRes, int yRes, PixelBounds bounds, const Filter* splatFilter = nullptr, bool moments = true);

    // Bytes a render holds at its peak for a film of `pixels` (crop region): the accumulators,
    // for splatting films the splat sums (per thread, or one shared array when those would
    // not fit) and their merged copy, and the images made from it (value, variance, sample
    // counts). Checked against the memory limit before a film is made.
    static double estimateBytes(double pixels, bool splats, int threads, bool moments = true);

    // Film "maxcomponentvalue" m (default infinity: no clamping) for every camera sample and
    // splat, each measured as the value it would have as one camera sample of its pixel: the
    // sample as given (imaging ratio included), a splat times imagingRatio times the widened
    // film's pixel count over the crop's (how image() scales splats per light path); its
    // components are those of `sensorFromL` times the sample (clampMaxComponent).
    void setMaxComponentValue(float m, float imagingRatio, const ClampSpace& sensorFromL = kIdentityClampSpace);
    // The same for a Markov chain's splats, as pbrt-v4's MLTIntegrator has it: each splat
    // (a sample's contribution over its target value, times its expected-value weight, before
    // the image's scale b / mutations per pixel) is clamped as it is given, with the imaging
    // ratio, which pbrt-v4's sensor applies to the splat and not to the target.
    void setChainMaxComponentValue(float m, float imagingRatio, const ClampSpace& sensorFromL);
    const ClampSpace& clampSpace() const { return clampSpace_; }
    float maxComponentValue() const { return maxComponent_; }

    int xRes() const { return xRes_; }
    int yRes() const { return yRes_; }
    const PixelBounds& bounds() const { return bounds_; }

    // Not thread-safe per pixel: callers own disjoint pixels (tiles). A non-finite L
    // counts as a black sample with its weight (as pbrt-v4 does) and is tallied, as is one
    // too large for the fixed-point sums (kMaxSampleValue).
    void addSample(int px, int py, Spectrum L, float weight, int sampleIndex = 0) {
        size_t i = index(px, py);
        L = clampMaxComponent(L, maxComponent_, clampSpace_);
        double y = L.luminance();
        if (!L.isFinite() || !(std::fabs(y) < kMaxSampleValue) ||
            !(std::max(std::fabs(L.r), std::max(std::fabs(L.g), std::fabs(L.b))) * std::fabs(weight) < kMaxSampleValue)) {
            L = Spectrum();
            y = 0;
            rejected_.fetch_add(1, std::memory_order_relaxed);
        }
        Pixel& p = pixels_[i];
        high_.carry(i, 0, addToSum(p.sum[0], double(L.r) * weight * kSumUnit));
        high_.carry(i, 1, addToSum(p.sum[1], double(L.g) * weight * kSumUnit));
        high_.carry(i, 2, addToSum(p.sum[2], double(L.b) * weight * kSumUnit));
        high_.carry(i, 3, addToSum(p.weight, double(weight) * kSumUnit));
        p.samples += 1;
        if (moments_.empty()) return;
        Moments& m = moments_[i];
        high_.carry(i, 4, addToSum(m.y, y * kSumUnit));
        const double yCapped = std::min(std::fabs(y), kMaxSquaredValue);
        high_.carry(i, 5, addToSum(m.y2, yCapped * yCapped * kFixedSquareUnit));
        if (splatFilter_) {
            Halves& h = halves_[i];
            h.y[sampleIndex & 1] += toFixed(y * weight);
            h.weight[sampleIndex & 1] += toFixed(weight);
        }
    }

    // Thread-safe and order-independent: splats accumulate in 64-bit fixed point, so the
    // image is bit-identical whatever the thread schedule. pFilm is a raster position.
    void addSplat(Vec2 pFilm, Spectrum L, int sampleIndex);
    // Starts loading the sums a splat at pFilm would update (a hint, no effect on results):
    // callers that know a splat's position before its visibility test hide the cache misses
    // of the splat behind the ray.
    void prefetchSplat(Vec2 pFilm, int sampleIndex);
    bool acceptsSplats() const { return splatFilter_ != nullptr; }

    // The image of the crop region: each pixel the weighted mean of its samples, plus the
    // splats normalised by the number of light paths traced (each carries importance
    // for the whole film, widened by the filter radius, so a pixel's share is that
    // widened film's pixel count / lightPaths).
    Image image(double lightPaths = 0) const;
    long long rejectedSamples() const { return rejected_.load(); }

    // The render's own error, as the thesis defines it (§2.4): per pixel, the variance of the
    // pixel's mean luminance estimated from its samples; over the image, the mean of those
    // variances, and the mean relative variance V/(mean^2 + 1e-3) (the small constant keeps
    // black pixels from dominating).
    struct ErrorEstimate {
        double meanVariance = 0;
        double meanRelativeVariance = 0;
    };
    ErrorEstimate errorEstimate(double lightPaths = 0) const;
    // The small constant of the relative variance V/(mean^2 + kRelativeEpsilon).
    static constexpr double kRelativeEpsilon = 1e-3;

    // Per pixel (crop region, row-major), the estimated variance of the pixel's mean
    // luminance, the quantity errorEstimate averages, as a grey image (all three channels
    // equal). From the pixel's own samples (assumed independent, so stratified samplers
    // overestimate it), or for splatting films from the two half-buffers.
    Image varianceImage(double lightPaths = 0) const;

    // What adaptive sampling needs to know about one pixel (non-splatting films): its
    // sample count and the mean and per-sample variance of its luminance samples.
    struct PixelEstimate {
        long long samples = 0;
        double mean = 0;
        double sampleVariance = 0;  // unbiased, per sample; 0 below two samples
        double varianceOfMean() const { return samples > 0 ? sampleVariance / double(samples) : 0.0; }
        double relativeVariance() const { return varianceOfMean() / (mean * mean + kRelativeEpsilon); }
    };
    PixelEstimate pixelEstimate(size_t pixel) const;
    size_t pixelCount() const { return pixels_.size(); }
    bool hasMoments() const { return !moments_.empty() || pixels_.empty(); }
    // Samples taken per pixel (crop region, row-major).
    std::vector<int> sampleCounts() const;
    // Pixels without samples take the other film's accumulators (same bounds, neither
    // splatting): lets a two-stage render that was stopped early fall back to its pilot.
    void adoptEmptyPixels(const Film& other);
    // Mean number of samples per pixel so far.
    double meanSamplesPerPixel() const;

    // Every sum the film holds, as exact integers: films of the same scene that took disjoint
    // sets of samples (processes of one render, distributed.h) add up, element by element, to
    // the film that took them all, bit for bit. `fixed`: the per-pixel sums; `counts`: the
    // per-pixel sample counts, the splat sums (splatting films) and the rejected samples.
    struct Accumulators {
        std::vector<Fixed> fixed;
        std::vector<int64_t> counts;
    };
    Accumulators accumulators() const;
    // Replaces every sum with `a` (as accumulators() gives them, for a film of the same bounds).
    void setAccumulators(const Accumulators& a);
    // The same, a range of pixels at a time (a reduction through a small buffer, without a
    // copy of the whole film): pixels [begin, end)'s kPixelSums sums and one count each, in
    // accumulators()'s order; and the counts after the pixels' (splat sums, rejected samples).
    static constexpr size_t kPixelSums = 10;
    void pixelSums(size_t begin, size_t end, Fixed* fixed, int64_t* counts) const;
    void setPixelSums(size_t begin, size_t end, const Fixed* fixed, const int64_t* counts);
    std::vector<int64_t> otherCounts() const;
    void setOtherCounts(const std::vector<int64_t>& counts);

    // Every per-pixel sum is an integer, exact and so independent of the order in which
    // samples arrive: the image does not depend on the thread schedule or on how the samples
    // were split over processes (see accumulators()). A camera sample's weighted values and
    // its luminance are rounded to the nearest multiple of 2^-40 (1e-12: below a float's
    // rounding for any pixel value over 1e-5), its squared luminance to 2^-32; each sum is
    // 64 bits with a 128-bit high word where needed (film/exact_sum.h), so the sums are
    // exact up to 2^127 units: |value| < kMaxSampleValue (2^40) per sample, 2^47 samples.
    // Squares would overflow sooner: a luminance above kMaxSquaredValue (3.4e10) enters the
    // variance estimate's sum of squares capped there (the estimate is then low, the image
    // exact), which keeps that sum below 2^126 over 2^23 samples.
    static constexpr double kSumUnit = 0x1p40, kFixedSquareUnit = 0x1p32;
    static constexpr double kMaxSampleValue = 0x1p40, kMaxSquaredValue = 0x1p35;
    // The 128-bit fixed point of the half-buffers and of other per-pixel sums that must add
    // up exactly over threads and processes (StrategyImages'): each value truncated to a
    // multiple of 2^-64; kMaxSampleValue bounds a value.
    static constexpr double kFixedUnit = 0x1p64;
    static Fixed toFixed(double v) { return truncateToFixed(v * kFixedUnit); }
    static double fromFixed(Fixed f) { return double(f) / kFixedUnit; }

private:
    // The low words of the sums (units of 2^-40: kSumUnit); their high words are in high_.
    struct Pixel {
        int64_t sum[3];
        int64_t weight;
        long long samples;
    };
    // The luminance and its square (units of 2^-40 and 2^-32), for the error estimate only:
    // apart from Pixel so that a film that is not asked for one does not carry them.
    struct Moments {
        int64_t y, y2;
    };
    // Pixel's and Moments' sums as whole integers, in accumulators()' order.
    static constexpr int kWideSums = 6;
    Fixed pixelSum(size_t i, int k) const;
    // The half-buffers' luminance and weight sums (even and odd sample indices), apart from
    // Pixel so that a film without splats or an error estimate does not carry them.
    struct Halves {
        Fixed y[2] = {0, 0}, weight[2] = {0, 0};
    };
    // Pixel's, Moments' and Halves' sums, in accumulators()'s order (a film without moments
    // or splats gives zeros for them and takes none).
    static constexpr size_t kFixedPerPixel = kPixelSums;
    // Variance of pixel i's mean luminance and that mean (the half-buffer estimate when splatting).
    double pixelVariance(size_t i, double lightPaths, const std::vector<int64_t>& splats, double& mean) const;
    static constexpr double kSplatFixedPoint = 268435456.0;  // 2^28 units per radiance unit
    static constexpr double kPerThreadSplatBytes = 1024.0 * 1024 * 1024;  // cap on all threads' splat copies
    static constexpr double kSplatBytesPerPixel = 6 * sizeof(int64_t);  // two halves' channel sums
    // Whether every thread gets its own splat sums (else one shared array of atomics).
    static bool perThreadSplatsFit(double pixels, int threads);
    // The film widened by the filter radius on every side, in pixels: the area over which
    // camera importance is spread (see Camera::setFilterMargin).
    double splatPixelCount() const {
        Vec2 r = splatFilter_->radius();
        return (double(xRes_) + 2 * r.x) * (double(yRes_) + 2 * r.y);
    }
    // The splat sums of every thread, merged (integer sums: the order does not matter).
    std::vector<int64_t> mergedSplats() const;
    // Splat sums are two planes, one per half-buffer, each [pixel][channel]: a splat touches
    // only its own half's cache lines.
    size_t splatOffset(size_t pixel, int half) const { return (size_t(half) * size_t(bounds_.area()) + pixel) * 3; }
    double splatValue(const std::vector<int64_t>& splats, size_t pixel, int half, int c) const {
        return double(splats[splatOffset(pixel, half) + size_t(c)]) / kSplatFixedPoint;
    }
    size_t index(int px, int py) const { return size_t(py - bounds_.y0) * bounds_.width() + (px - bounds_.x0); }

    int xRes_, yRes_;
    PixelBounds bounds_;
    float maxComponent_ = std::numeric_limits<float>::infinity();
    float splatMaxComponent_ = std::numeric_limits<float>::infinity();  // the same, in splat units
    ClampSpace clampSpace_ = kIdentityClampSpace;
    ZeroedArray<Pixel> pixels_;
    ZeroedArray<Moments> moments_;  // films with an error estimate only, one per pixel
    HighWords<kWideSums> high_;
    ZeroedArray<Halves> halves_;  // splatting films with an error estimate only, one per pixel
    std::atomic<long long> rejected_{0};
    const Filter* splatFilter_ = nullptr;
    // Splat sums [pixel][half][channel]: per thread without atomics when they fit in memory
    // (an atomic add per splat and channel costs more than the connection that made it),
    // else one shared array of atomics.
    bool perThreadSplats_ = false;
    tbb::enumerable_thread_specific<std::vector<int64_t>> threadSplats_;
    int64_t* threadSplatSums();  // the calling thread's sums (per-thread films)
    // The pixels whose filter footprint covers raster position pFilm, clipped to the film
    // (empty when x0 > x1 or y0 > y1): what a splat there updates.
    struct PixelRange {
        int x0, x1, y0, y1;
    };
    PixelRange splatFootprint(Vec2 pFilm) const;
    uint64_t id_ = 0;            // unique per film, keys threadSplatSums' per-thread cache
    double splatUnitsPerWeight_ = 0;  // fixed-point units per unit of filter weight / integral
    std::unique_ptr<std::atomic<int64_t>[]> splats_;
};

}  // namespace ps
