#include "media/cloud_medium.h"

#include <algorithm>
#include <cmath>
#include "materials/noise.h"

namespace ps {

namespace {

// The octaves' weights: 1/2, 1/4, ... (their sum bounds the noise sum over kNoiseBound).
constexpr int kOctaves = 5;
constexpr float kOctaveWeightSum = 0.5f + 0.25f + 0.125f + 0.0625f + 0.03125f;

}  // namespace

CloudMedium::CloudMedium(const MediumBox& box, MediumSpectrum sigmaA, MediumSpectrum sigmaS, float g, Shape shape)
    : DensityMedium(box, std::move(sigmaA), std::move(sigmaS), g, 16), shape_(shape) {
    majorants_.fill([&](Vec3 lo, Vec3 hi) { return cellBound(lo, hi); });
}

float CloudMedium::density(Vec3 p) const {
    Vec3 q = p * shape_.frequency;
    if (shape_.wispiness > 0) {
        // Two octaves of displacement (amplitude 0.05 wispiness, halving; frequency 10,
        // growing by 1.99) turn the noise's blobs into wisps, as pbrt-v4 does.
        float amplitude = 0.05f * shape_.wispiness, scale = 10;
        for (int i = 0; i < 2; ++i) {
            q = q + perlinNoiseDifference(q * scale) * amplitude;
            amplitude *= 0.5f;
            scale *= kOctaveLacunarity;
        }
    }
    // Fractal sum: weights halve and frequencies grow by 1.99 (not 2, so that the octaves'
    // lattices do not line up).
    float sum = 0, weight = 0.5f, scale = 1;
    for (int i = 0; i < kOctaves; ++i) {
        sum += weight * perlinNoise(q * scale);
        weight *= 0.5f;
        scale *= kOctaveLacunarity;
    }
    // Thinning with height, then a solid base: 1 at y <= 0, fading in below y = 1/2.
    float d = std::clamp((1 - p.y) * 4.5f * shape_.density * sum, 0.0f, 1.0f);
    d += 2 * std::max(0.0f, 0.5f - p.y);
    return std::clamp(d, 0.0f, 1.0f);
}

float CloudMedium::cellBound(Vec3 lo, Vec3 hi) const {
    // Only height is bounded tightly: the noise term is at most |1 - y| 4.5 |density| times
    // the octaves' sum of |noise| <= kPerlinNoiseBound, the base 2 max(0, 1/2 - y). Both are
    // monotone in y over each side of y = 1, so their ends (widened by 1% of the cell against
    // rounding) bound them. A conservative bound keeps tracking unbiased; it lowers the
    // majorant only where the noise cannot reach 1, near y = 1.
    const float e = box_.p1.y - box_.p0.y, pad = 0.01f * (hi.y - lo.y) * e;
    const float y0 = box_.p0.y + lo.y * e - pad, y1 = box_.p0.y + hi.y * e + pad;
    const float maxDistFrom1 = (y0 <= 1 && y1 >= 1) ? std::max(1 - y0, y1 - 1) : std::max(std::abs(1 - y0), std::abs(1 - y1));
    const float noiseTerm = std::min(1.0f, maxDistFrom1 * 4.5f * std::abs(shape_.density) * kPerlinNoiseBound * kOctaveWeightSum);
    const float base = 2 * std::max(0.0f, 0.5f - y0);
    return std::min(1.0f, noiseTerm + base);
}

}  // namespace ps
