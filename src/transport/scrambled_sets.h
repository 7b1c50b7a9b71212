// The variance of a stratified or QMC render from independent scramblings (`--stats`;
// docs/strategy-figures.md). A pixel's s^2 / n treats its samples as independent, which
// stratified and randomised QMC points are not: it overstates their variance and hides their
// gain. Rendered as K independently randomised point sets (RenderOptions::scramblings: sample
// i of a pixel is sample i / K of set i mod K, each set with a seed of its own, so that a render
// stopped early by --time fills them alike), the K set means of a pixel are independent and
// unbiased, and their spread gives the variance of the pixel's mean honestly (Owen's
// replicated randomised QMC; thesis §2.6 on stratification's variance).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "film/film.h"

namespace ps {

// Batches for `spp` samples per pixel: 8 (fewer below 32 spp, each of 4 points at least, so
// that a set keeps its sampler's structure), 1 below 8 spp.
int batchCount(int spp);
// K for a render of `spp` samples per pixel with `sampler`: batchCount(spp) scrambled sets,
// or 1 where the samples are independent already (`independent`).
int scramblingCount(const std::string& sampler, int spp);
// Where ranges 2..K of `spp` sample indices begin (as even as may be): the technique figures'
// batches over one scrambled sequence (SamplePasses).
std::vector<int> scramblingStarts(int spp, int sets);

// Per pixel and set: the sums of a pixel's sample luminances (as the film's moments take
// them). Each pixel is written by the thread that owns its tile.
class ScrambledPixelVariance {
public:
    ScrambledPixelVariance(size_t pixels, int sets);
    void add(int set, size_t pixel, double y) {
        const size_t i = size_t(set) * pixels_ + pixel;
        sum_[i] += y;
        ++count_[i];
    }
    // The film's error estimate (Film::ErrorEstimate, its relative epsilon) with each pixel's
    // variance from the spread of its set means.
    Film::ErrorEstimate errorEstimate() const;

private:
    size_t pixels_;
    int sets_;
    std::vector<double> sum_;  // [set][pixel]
    std::vector<int> count_;   // [set][pixel]
};

}  // namespace ps
