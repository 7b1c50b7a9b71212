#include "transport/technique_tally.h"

#include <algorithm>
#include <numeric>

#include "mc/estimator.h"

namespace ps {

TechniqueTally::TechniqueTally(int techniques, int sets, Vec2 lo, Vec2 hi)
    : techniques_(techniques), sets_(std::max(1, sets)), lo_(lo), hi_(hi), current_(size_t(techniques), 0.0),
      splatCurrent_(size_t(techniques), 0.0), sums_(size_t(sets_) * size_t(techniques + 1) * kMoments, 0.0),
      weight_(size_t(sets_), 0.0), count_(size_t(sets_), 0) {}

void TechniqueTally::endSample(int set, double cameraScale, double splatScale, double filterWeight) {
    double wholeC = 0, wholeS = 0;
    auto add = [&](int k, double c, double s) {
        at(set, k, kC) += c;
        at(set, k, kS) += s;
        at(set, k, kCC) += c * c;
        at(set, k, kCS) += c * s;
        at(set, k, kSS) += s * s;
    };
    for (int k = 0; k < techniques_; ++k) {
        const double c = current_[size_t(k)] * cameraScale, s = splatCurrent_[size_t(k)] * splatScale;
        current_[size_t(k)] = splatCurrent_[size_t(k)] = 0;
        wholeC += c;
        wholeS += s;
        add(k, c, s);
    }
    add(techniques_, wholeC, wholeS);
    weight_[size_t(set)] += filterWeight;
    ++count_[size_t(set)];
}

void TechniqueTally::merge(const TechniqueTally& o) {
    if (o.empty()) return;
    if (empty()) {
        *this = o;
        return;
    }
    for (size_t i = 0; i < sums_.size(); ++i) sums_[i] += o.sums_[i];
    for (size_t b = 0; b < count_.size(); ++b) {
        weight_[b] += o.weight_[b];
        count_[b] += o.count_[b];
    }
}

long long TechniqueTally::samples() const { return std::accumulate(count_.begin(), count_.end(), 0LL); }

std::vector<TechniqueTally::Figure> TechniqueTally::figures(double seconds) const {
    std::vector<Figure> out(size_t(techniques_ + 1));
    const double n = double(samples());
    const double meanWeight = std::accumulate(weight_.begin(), weight_.end(), 0.0) / n;
    if (n < 2 || meanWeight == 0) return out;
    // Y = C / (mean filter weight) + S: a pixel's camera samples are normalised by their
    // weights' sum, splats by the number of samples.
    const double a = 1 / meanWeight;
    int filledSets = 0;
    for (long long c : count_) filledSets += c > 0;
    for (int k = 0; k <= techniques_; ++k) {
        Figure& f = out[size_t(k)];
        double total = 0, totalSq = 0;
        std::vector<double> setSum(size_t(sets_), 0.0);
        for (int b = 0; b < sets_; ++b) {
            setSum[size_t(b)] = a * at(b, k, kC) + at(b, k, kS);
            total += setSum[size_t(b)];
            totalSq += a * a * at(b, k, kCC) + 2 * a * at(b, k, kCS) + at(b, k, kSS);
        }
        f.mean = total / n;
        if (sets_ == 1) {
            // Independent samples: the sample variance of Y over N.
            f.variance = std::max(0.0, (totalSq - total * total / n) / (n - 1)) / n;
        } else if (filledSets >= 2) {
            // Independent sets (each stratified or QMC within): the spread of their means,
            // each weighted by its sample count, Var(M) = sum n_b (M_b - M)^2 / ((K - 1) N).
            double ss = 0;
            for (int b = 0; b < sets_; ++b) {
                if (count_[size_t(b)] == 0) continue;
                const double mb = setSum[size_t(b)] / double(count_[size_t(b)]);
                ss += double(count_[size_t(b)]) * (mb - f.mean) * (mb - f.mean);
            }
            f.variance = ss / (double(filledSets - 1) * n);
        }
    }
    const double image = out[size_t(techniques_)].mean;
    for (Figure& f : out) {
        f.share = image != 0 ? f.mean / image : 0.0;
        f.relativeVariance = image != 0 ? f.variance / (image * image) : 0.0;
        f.efficiency = efficiency(f.relativeVariance, seconds);
    }
    return out;
}

}  // namespace ps
