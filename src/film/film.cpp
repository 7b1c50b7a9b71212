#include "film/film.h"

#include <cmath>

namespace ps {

Film::Film(int xRes, int yRes, PixelBounds bounds)
    : xRes_(xRes), yRes_(yRes), bounds_(bounds), pixels_(size_t(bounds.area())) {}

Image Film::image() const {
    Image img(bounds_.width(), bounds_.height());
    for (int y = 0; y < bounds_.height(); ++y)
        for (int x = 0; x < bounds_.width(); ++x) {
            const Pixel& p = pixels_[size_t(y) * bounds_.width() + x];
            Spectrum v;
            if (p.weight != 0)
                v = Spectrum(float(p.sum[0] / p.weight), float(p.sum[1] / p.weight), float(p.sum[2] / p.weight));
            if (!v.isFinite()) v = Spectrum();
            img.set(x, y, v);
        }
    return img;
}

Film::ErrorEstimate Film::errorEstimate() const {
    ErrorEstimate e;
    if (pixels_.empty()) return e;
    for (const Pixel& p : pixels_) {
        double n = double(p.samples);
        if (n < 2) continue;
        double m = p.sumY / n;
        double v = std::max(0.0, (p.sumY2 - n * m * m) / (n - 1)) / n;  // variance of the mean
        e.meanVariance += v;
        e.meanRelativeVariance += v / (m * m + 1e-3);
    }
    e.meanVariance /= double(pixels_.size());
    e.meanRelativeVariance /= double(pixels_.size());
    return e;
}

double Film::meanSamplesPerPixel() const {
    long double total = 0;
    for (const Pixel& p : pixels_) total += p.samples;
    return pixels_.empty() ? 0.0 : double(total / pixels_.size());
}

}  // namespace ps
