#include "camera/aperture_mask.h"

#include <algorithm>
#include <cmath>

namespace ps {

namespace {
constexpr int kBuiltinRes = 256;
}

void ApertureMask::flipRows() {
    for (int y = 0; y < h_ / 2; ++y)
        for (int x = 0; x < w_; ++x) std::swap(at(x, y), at(x, h_ - 1 - y));
}

void ApertureMask::normalise() {
    double sum = 0;
    for (float v : v_) sum += v;
    double mean = sum / double(v_.size());
    if (!(mean > 0)) return;  // an all-black mask stays black: every ray is blocked
    float scale = float((kPi / 4) / mean);
    for (float& v : v_) v *= scale;
}

ApertureMask ApertureMask::polygon(const std::vector<Vec2>& vert) {
    ApertureMask m(kBuiltinRes, kBuiltinRes);
    const size_t n = vert.size();
    for (int y = 0; y < kBuiltinRes; ++y)
        for (int x = 0; x < kBuiltinRes; ++x) {
            Vec2 p(-1 + 2 * (x + 0.5f) / kBuiltinRes, -1 + 2 * (y + 0.5f) / kBuiltinRes);
            // Crossing parity of a ray towards +x: the polygons are simple, so parity is inside.
            bool inside = false;
            for (size_t i = 0, j = n - 1; i < n; j = i++) {
                Vec2 a = vert[j], b = vert[i];
                if ((a.y > p.y) != (b.y > p.y)) {
                    float xCross = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                    if (p.x < xCross) inside = !inside;
                }
            }
            m.at(x, y) = inside ? 1.0f : 0.0f;
        }
    return m;
}

bool ApertureMask::builtin(const std::string& name, ApertureMask* out) {
    ApertureMask m(kBuiltinRes, kBuiltinRes);
    if (name == "gaussian") {
        // exp(-r^2) minus its value at the stop's rim, so it falls to zero there.
        for (int y = 0; y < kBuiltinRes; ++y)
            for (int x = 0; x < kBuiltinRes; ++x) {
                float u = -1 + 2 * (x + 0.5f) / kBuiltinRes, v = -1 + 2 * (y + 0.5f) / kBuiltinRes;
                m.at(x, y) = std::max(0.0f, std::exp(-(u * u + v * v)) - std::exp(-1.0f));
            }
    } else if (name == "square") {
        // The middle half of each side.
        for (int y = kBuiltinRes / 4; y < kBuiltinRes * 3 / 4; ++y)
            for (int x = kBuiltinRes / 4; x < kBuiltinRes * 3 / 4; ++x) m.at(x, y) = 1;
    } else if (name == "pentagon") {
        // A regular pentagon with a vertex at (0, 1), scaled by 0.8.
        std::vector<Vec2> v;
        for (int i = 0; i < 5; ++i) {
            float a = kPi / 2 - 2 * kPi * i / 5;
            v.push_back(Vec2(std::cos(a), std::sin(a)) * 0.8f);
        }
        m = polygon(v);
    } else if (name == "star") {
        // Five points on the unit circle at odd multiples of 36 degrees, inner vertices at
        // the radius where the pentagram's edges cross.
        std::vector<Vec2> v;
        const float inner = std::cos(radians(72.0f)) / std::cos(radians(36.0f));
        for (int i = 0; i < 10; ++i) {
            float r = (i & 1) ? 1.0f : inner, a = kPi * i / 5;
            v.push_back(Vec2(r * std::cos(a), r * std::sin(a)));
        }
        m = polygon(v);
    } else {
        return false;
    }
    m.flipRows();
    m.normalise();
    *out = std::move(m);
    return true;
}

ApertureMask ApertureMask::fromImage(const Image& img) {
    ApertureMask m(img.width, img.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            Spectrum c = img.get(x, y);
            m.at(x, y) = (c[0] + c[1] + c[2]) / 3;
        }
    m.flipRows();
    m.normalise();
    return m;
}

float ApertureMask::lookup(Vec2 uv) const {
    if (w_ == 0 || !(std::isfinite(uv.x) && std::isfinite(uv.y))) return 0;
    float x = uv.x * w_ - 0.5f, y = uv.y * h_ - 0.5f;
    float fx = std::floor(x), fy = std::floor(y);
    if (fx < -1 || fy < -1 || fx > float(w_) || fy > float(h_)) return 0;
    int x0 = int(fx), y0 = int(fy);
    float dx = x - fx, dy = y - fy;
    auto T = [&](int xi, int yi) { return xi < 0 || yi < 0 || xi >= w_ || yi >= h_ ? 0.0f : texel(xi, yi); };
    return (1 - dx) * (1 - dy) * T(x0, y0) + dx * (1 - dy) * T(x0 + 1, y0) + (1 - dx) * dy * T(x0, y0 + 1) +
           dx * dy * T(x0 + 1, y0 + 1);
}

}  // namespace ps
