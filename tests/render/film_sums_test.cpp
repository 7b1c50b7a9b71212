// The film's sums are exact (fixed point): the same samples in any order, or split over
// several films whose accumulators are then added (the processes of one render), give the
// same image and variance image, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "film/film.h"
#include "film/filter.h"
#include "mc/rng.h"

using namespace ps;

namespace {

struct Sample {
    int x, y, index;
    Spectrum L;
    float weight;
    Vec2 splat;
};

// Values over twelve orders of magnitude: sums of them in double precision would round, and
// depend on their order (over six, float values still sum exactly in a double).
std::vector<Sample> samples(int n) {
    std::vector<Sample> s;
    Rng rng(7);
    for (int i = 0; i < n; ++i) {
        auto value = [&] { return float(std::pow(10.0, 12 * rng.uniform() - 6)); };
        s.push_back({int(rng.uniform() * 5), int(rng.uniform() * 4), i, Spectrum(value(), value(), value()),
                     0.5f + rng.uniform(), Vec2(5 * rng.uniform(), 4 * rng.uniform())});
    }
    return s;
}

void add(Film& f, const Sample& s) {
    f.addSample(s.x, s.y, s.L, s.weight, s.index);
    f.addSplat(s.splat, s.L * 0.1f, s.index);
}

bool sameBits(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) return false;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            Spectrum p = a.get(x, y), q = b.get(x, y);
            if (std::memcmp(&p, &q, sizeof p) != 0) return false;
        }
    return true;
}

}  // namespace

TEST(FilmSums, IndependentOfOrderAndSplit) {
    const PixelBounds bounds{0, 5, 0, 4};
    BoxFilter box(Vec2(0.5f, 0.5f));
    for (const Filter* filter : {static_cast<const Filter*>(nullptr), static_cast<const Filter*>(&box)}) {
        SCOPED_TRACE(filter ? "splatting film" : "camera samples only");
        const std::vector<Sample> s = samples(4000);
        Film inOrder(5, 4, bounds, filter), reversed(5, 4, bounds, filter), merged(5, 4, bounds, filter);
        for (const Sample& x : s) add(inOrder, x);
        for (auto it = s.rbegin(); it != s.rend(); ++it) add(reversed, *it);
        // Three "processes", each every third sample; their sums added element by element.
        Film::Accumulators total;
        for (int part = 0; part < 3; ++part) {
            Film f(5, 4, bounds, filter);
            for (const Sample& x : s)
                if (x.index % 3 == part) add(f, x);
            Film::Accumulators a = f.accumulators();
            if (part == 0) total = a;
            else {
                ASSERT_EQ(a.fixed.size(), total.fixed.size());
                ASSERT_EQ(a.counts.size(), total.counts.size());
                for (size_t i = 0; i < a.fixed.size(); ++i) total.fixed[i] += a.fixed[i];
                for (size_t i = 0; i < a.counts.size(); ++i) total.counts[i] += a.counts[i];
            }
        }
        merged.setAccumulators(total);
        const double lightPaths = double(s.size());
        for (const Film* f : {&reversed, &merged}) {
            EXPECT_TRUE(sameBits(f->image(lightPaths), inOrder.image(lightPaths)));
            EXPECT_TRUE(sameBits(f->varianceImage(lightPaths), inOrder.varianceImage(lightPaths)));
            EXPECT_EQ(f->sampleCounts(), inOrder.sampleCounts());
            EXPECT_EQ(f->meanSamplesPerPixel(), inOrder.meanSamplesPerPixel());
            // In double precision too (the images' floats would hide most rounding differences).
            for (size_t i = 0; i < f->pixelCount(); ++i) {
                Film::PixelEstimate e = f->pixelEstimate(i), r = inOrder.pixelEstimate(i);
                EXPECT_EQ(std::memcmp(&e.mean, &r.mean, sizeof(double)), 0) << "pixel " << i << ": " << e.mean << " vs " << r.mean;
                EXPECT_EQ(std::memcmp(&e.sampleVariance, &r.sampleVariance, sizeof(double)), 0) << "pixel " << i;
            }
        }
        // And the sums are those of the samples: pixel (0, 0)'s mean, to double rounding.
        double sum = 0, weight = 0;
        for (const Sample& x : s)
            if (x.x == 0 && x.y == 0) sum += double(x.L.r) * x.weight, weight += x.weight;
        if (!filter) {
            EXPECT_NEAR(inOrder.image().get(0, 0).r, sum / weight, 1e-6 * sum / weight);
        }
    }
}

// Luminances near the film's limit (2^40 per sample) over 2^23 samples: the sums of squares
// stay within 128 bits (the variance estimate caps a sample's luminance at 2^35 there) and the
// mean is exact. Without the cap the sum of squares overflows (and UBSan reports it).
TEST(FilmSums, HugeSamplesDoNotOverflowTheSquares) {
    PixelBounds b{0, 1, 0, 1};
    Film film(1, 1, b, nullptr);
    const float v = 1e11f;  // luminance 1e11 < 2^40 = 1.1e12
    const int n = 1 << 23;
    for (int i = 0; i < n; ++i) film.addSample(0, 0, Spectrum(v, v, v), 1.0f, i);
    const Image img = film.image(0);
    const Film::PixelEstimate e = film.pixelEstimate(0);
    std::printf("mean %.6g (exact %.6g), sample variance %.3g, rejected %lld\n", img.get(0, 0).r, double(v),
                e.sampleVariance, film.rejectedSamples());
    EXPECT_FLOAT_EQ(img.get(0, 0).r, v);
    EXPECT_EQ(film.rejectedSamples(), 0);
    EXPECT_TRUE(std::isfinite(e.sampleVariance));
    EXPECT_GE(e.sampleVariance, 0.0);
    // The sum of squares (index 5 of a pixel's accumulators, in units of 2^-32): n samples
    // of the cap squared, 2^23 * 2^70 * 2^32 = 2^125 exactly.
    EXPECT_TRUE(film.accumulators().fixed[5] == Fixed(1) << 125) << "the sum of squares overflowed or was not capped";
}

// Sums that leave 64 bits (a light seen directly at many samples) carry into their high
// words: in any order and split, the film's sums are the exact integer sums of the rounded
// values (computed here in 128 bits independently), and the image is the same bit for bit.
TEST(FilmSums, SumsPastSixtyFourBitsAreExact) {
    const PixelBounds bounds{0, 3, 0, 1};
    std::vector<Sample> s;
    Rng rng(11);
    // Pixel 0: large values (each near 2^20 radiance units: 2^63 units in about 8 of
    // them), some negative so that the sum crosses the limit both ways; pixel 1: values
    // large enough to need a high word each (|v| 2^40 >= 2^62); pixel 2: ordinary values.
    for (int i = 0; i < 300000; ++i) {
        const int x = i % 3;
        float v = x == 0 ? float((rng.uniform() < 0.8 ? 1 : -1) * 0x1p20 * (0.5 + rng.uniform()))
                  : x == 1 ? float(0x1p24 * (1 + rng.uniform()))
                           : float(rng.uniform());
        s.push_back({x, 0, i, Spectrum(v, 0.5f * v, 0.25f), 0.5f + rng.uniform(), Vec2()});
    }
    Film inOrder(3, 1, bounds), reversed(3, 1, bounds), merged(3, 1, bounds);
    for (const Sample& x : s) inOrder.addSample(x.x, x.y, x.L, x.weight, x.index);
    for (auto it = s.rbegin(); it != s.rend(); ++it) reversed.addSample(it->x, it->y, it->L, it->weight, it->index);
    Film::Accumulators total;
    for (int part = 0; part < 2; ++part) {
        Film f(3, 1, bounds);
        for (const Sample& x : s)
            if ((x.index / 7) % 2 == part) f.addSample(x.x, x.y, x.L, x.weight, x.index);
        Film::Accumulators a = f.accumulators();
        if (part == 0) total = a;
        else
            for (size_t i = 0; i < a.fixed.size(); ++i) total.fixed[i] += a.fixed[i];
    }
    for (size_t i = 0; i < 3; ++i) total.counts[i] = inOrder.accumulators().counts[i];
    merged.setAccumulators(total);
    // The red and weight sums of each pixel, exactly: each term rounded to a multiple of 2^-40.
    Fixed red[3] = {0, 0, 0}, weight[3] = {0, 0, 0};
    for (const Sample& x : s) {
        red[x.x] += Fixed(std::nearbyint(double(x.L.r) * x.weight * Film::kSumUnit));
        weight[x.x] += Fixed(std::nearbyint(double(x.weight) * Film::kSumUnit));
    }
    EXPECT_TRUE(red[0] > Fixed(1) << 64 && red[1] > Fixed(1) << 70) << "the sums should need high words";
    for (const Film* f : {&inOrder, &reversed, &merged}) {
        const Film::Accumulators a = f->accumulators();
        for (int p = 0; p < 3; ++p) {
            EXPECT_TRUE(a.fixed[size_t(p) * Film::kPixelSums + 0] == red[p]) << "pixel " << p;
            EXPECT_TRUE(a.fixed[size_t(p) * Film::kPixelSums + 3] == weight[p]) << "pixel " << p;
        }
        EXPECT_TRUE(sameBits(f->image(), inOrder.image()));
        EXPECT_TRUE(sameBits(f->varianceImage(), inOrder.varianceImage()));
    }
    // And the image is made from the whole sums.
    for (int p = 0; p < 3; ++p)
        EXPECT_EQ(inOrder.image().get(p, 0).r, float(double(red[p]) / double(weight[p]))) << "pixel " << p;
    EXPECT_EQ(inOrder.rejectedSamples(), 0);
}

// A film without the error estimate's moments makes the same image, bit for bit, and
// estimates nothing.
TEST(FilmSums, MomentsDoNotChangeTheImage) {
    const PixelBounds bounds{0, 5, 0, 4};
    Film with(5, 4, bounds, nullptr, true), without(5, 4, bounds, nullptr, false);
    for (const Sample& x : samples(2000)) {
        with.addSample(x.x, x.y, x.L, x.weight, x.index);
        without.addSample(x.x, x.y, x.L, x.weight, x.index);
    }
    EXPECT_TRUE(sameBits(with.image(), without.image()));
    EXPECT_GT(with.errorEstimate().meanVariance, 0.0);
    EXPECT_EQ(without.errorEstimate().meanVariance, 0.0);
    EXPECT_TRUE(without.hasMoments() == false && with.hasMoments());
}
