#include "spectral/rgb_to_spectrum.h"
#include "spectral/rgb_table_layout.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

// The four tables, embedded by rgb_tables_embed.cpp, in colour-space index order.
extern "C" const float ps_rgb2spec_table_0[];
extern "C" const float ps_rgb2spec_table_1[];
extern "C" const float ps_rgb2spec_table_2[];
extern "C" const float ps_rgb2spec_table_3[];

namespace ps {

uint64_t rgbTableExpectedChecksum(int space);  // rgb_tables_embed.cpp

static_assert(kRgbTableRes == 64);

RGBToSpectrumTable::RGBToSpectrumTable(const float* coefficients, uint64_t expected)
    : coefficients_(coefficients), expected_(expected) {
    for (int k = 0; k < kRgbTableRes; ++k) brightness_[size_t(k)] = rgbTableBrightness(k);
}

const RGBToSpectrumTable& RGBToSpectrumTable::forSpace(const RGBColorSpace& space) {
    static const float* const kData[kNamedColorSpaces] = {ps_rgb2spec_table_0, ps_rgb2spec_table_1,
                                                          ps_rgb2spec_table_2, ps_rgb2spec_table_3};
    static std::unique_ptr<RGBToSpectrumTable> cache[kNamedColorSpaces];
    static std::once_flag once[kNamedColorSpaces];
    const int i = space.index;
    std::call_once(once[i], [&] {
        cache[i].reset(new RGBToSpectrumTable(kData[i], rgbTableExpectedChecksum(i)));
    });
    return *cache[i];
}

uint64_t RGBToSpectrumTable::checksum() const {
    const unsigned char* b = reinterpret_cast<const unsigned char*>(coefficients_);
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < kRgbTableFloats * sizeof(float); ++i) h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

SigmoidPolynomial RGBToSpectrumTable::operator()(std::array<float, 3> rgb) const {
    for (float& v : rgb) v = v >= 0 ? std::min(v, 1.0f) : 0.0f;  // NaN too: no index is made of it
    if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) {
        // S(c2) = v  <=>  c2 = (v - 1/2) / sqrt(v (1 - v)); +-infinity at 1 and 0.
        const float v = rgb[0];
        return {0, 0, (v - 0.5f) / std::sqrt(v * (1 - v))};
    }
    const int m = rgb[0] > rgb[1] ? (rgb[0] > rgb[2] ? 0 : 2) : (rgb[1] > rgb[2] ? 1 : 2);
    const float z = rgb[size_t(m)];
    const float x = rgb[size_t((m + 1) % 3)] * (kRgbTableRes - 1) / z;
    const float y = rgb[size_t((m + 2) % 3)] * (kRgbTableRes - 1) / z;
    const int xi = std::min(int(x), kRgbTableRes - 2), yi = std::min(int(y), kRgbTableRes - 2);
    // The last brightness node below z (the first interval when z is at or below node 0).
    const int zi = std::clamp(int(std::lower_bound(brightness_.begin(), brightness_.end(), z) - brightness_.begin()) - 1, 0,
                              kRgbTableRes - 2);
    const float dx = x - float(xi), dy = y - float(yi);
    const float dz = (z - brightness_[size_t(zi)]) / (brightness_[size_t(zi) + 1] - brightness_[size_t(zi)]);
    float c[3];
    for (int n = 0; n < 3; ++n) {
        auto at = [&](int ox, int oy, int oz) { return coefficients_[rgbTableIndex(m, zi + oz, yi + oy, xi + ox) + size_t(n)]; };
        auto lerp = [](float t, float a, float b) { return (1 - t) * a + t * b; };
        c[n] = lerp(dz, lerp(dy, lerp(dx, at(0, 0, 0), at(1, 0, 0)), lerp(dx, at(0, 1, 0), at(1, 1, 0))),
                    lerp(dy, lerp(dx, at(0, 0, 1), at(1, 0, 1)), lerp(dx, at(0, 1, 1), at(1, 1, 1))));
    }
    return {c[0], c[1], c[2]};
}

}  // namespace ps
