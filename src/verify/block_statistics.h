// Agreement of independent unbiased estimators, measured (thesis §1.4 and ch. 10: an unbiased
// estimator's error is only variance, so two of them may differ only by what their spread
// allows). An image is summarised by the mean luminance of a grid of blocks and of the whole
// image; K independent renders of one estimator give each summary's mean and standard error
// from their spread across renders, never from one render's per-sample variance (a Markov
// chain's samples are correlated). Used by `pathspace verify` and the agreement matrix.
#pragma once
#include <string>
#include <vector>

#include "image/image.h"

namespace ps::verify {

struct Estimate {
    double mean = 0, stdErr = 0;
};

// The luminance (Rec. 709) and R, G, B means of one image's blocks and of the whole image.
struct ImageSummary {
    std::vector<double> blocks;    // nx * ny, row-major, row 0 at the top
    double image = 0;              // luminance of the whole image
    double channels[3] = {0, 0, 0};
};
ImageSummary summarise(const Image& img, int nx, int ny);

// Which of nx x ny blocks pixel (x, y) of a w x h image falls in (row-major), and the pixels
// block i covers, x0 <= x < x1 and y0 <= y < y1: the one assignment summarise() uses.
int blockOf(int x, int y, int nx, int ny, int w, int h);
struct BlockPixels {
    int x0, x1, y0, y1;
};
BlockPixels blockPixels(int i, int nx, int ny, int w, int h);

// K independent renders of one estimator.
class RunSet {
public:
    RunSet(int nx = 4, int ny = 4) : nx_(nx), ny_(ny) {}
    void add(const Image& img);
    int runs() const { return int(runs_.size()); }
    int blocksX() const { return nx_; }
    int blocksY() const { return ny_; }
    int blockCount() const { return nx_ * ny_; }
    Estimate block(int i) const;
    Estimate image() const;
    Estimate channel(int c) const;
    // The mean of the renders, pixel by pixel (for maps of where estimators differ).
    const Image& meanImage() const { return sum_; }

private:
    int nx_, ny_;
    std::vector<ImageSummary> runs_;
    Image sum_;  // running mean
};

// What an estimator is compared with: per block and for the image, a value and its standard
// error (0 for an exact answer).
struct Reference {
    std::string what;  // "exact", "the scene without the feature", "the pooled path, bdpt, ..."
    std::vector<Estimate> blocks;
    Estimate image;
    Estimate channels[3];
    bool compareChannels = true;
    // The degrees of freedom of its standard errors (renders - 1, summed over the estimators
    // it pools; huge for an exact answer).
    double dof = 1e9;
};
Reference referenceFrom(const RunSet& runs, const std::string& what);
// Every pixel's luminance (and each channel) equal to `value`: a uniform exact image.
Reference exactReference(double value, int blockCount);
// The inverse-variance weighted mean of several estimators that agree, summary by summary,
// and its standard error (verify.cpp chooses which: an estimator that disagrees with the
// others must not be among them).
Reference pooledOf(const std::vector<const RunSet*>& others, const std::string& what);

// How far an estimator is from a reference. Standard errors estimated from K renders make
// a difference over its error Student-t distributed (Welch's degrees of freedom), with far
// heavier tails than a normal's at K = 8: each test below takes "4 sigma" to mean the t value
// with a normal's 4-sigma tail probability (6.3e-5), so that the many cells of a matrix do
// not fail by chance. It agrees when
// - the image mean is within 4 such sigma (the pooled statistic of every block) and, where
//   the reference has colour, so is each channel's;
// - the sum over blocks of squared z-scores is below the chi-square bound for that many blocks
//   at p = 1e-6, each block's t value taken to the normal deviate of equal tail probability;
// - no block differs by more than 4 standard errors plus `blockFloor` of the image mean (dim
//   blocks of heavy-tailed estimates have standard errors that few renders underestimate).
// `resolution` is the smallest uniform relative bias the image test would catch: its
// critical value times sigma, over the mean. A comparison whose resolution is above what a caller needs proves little.
struct Verdict {
    double ratio = 1;       // image mean over the reference's
    double imageZ = 0;      // signed, in standard errors (a t value)
    double critical = 4;    // the image test's bound on |imageZ|
    double channelZ[3] = {0, 0, 0};
    double resolution = 0;  // 4 sigma / reference mean
    double chi2 = 0, chi2Limit = 0;
    std::vector<double> blockZ;  // signed, per block: normal deviates (see above)
    int worstBlock = -1;
    int blocksBeyond = 0;        // blocks past 4 sigma + floor
    bool agrees = true;
    std::string why;             // what failed, empty when it agrees
};
Verdict compare(const RunSet& x, const Reference& ref, double blockFloor = 0.01);

// The chi-square distribution's upper quantile at probability p (Wilson-Hilferty).
double chiSquareUpperQuantile(int dof, double p);
// Student's t: the probability of |T| > t with nu degrees of freedom, and the t whose
// two-sided tail is a normal's beyond 4 sigma.
double studentTwoSidedTail(double t, double nu);
double fourSigmaEquivalent(double nu);

}  // namespace ps::verify
