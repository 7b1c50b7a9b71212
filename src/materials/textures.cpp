#include "materials/textures.h"

#include <map>
#include <mutex>

namespace ps {

bool ImageLookup::texel(int x, int y, Spectrum& out) const {
    int w = img_->width, h = img_->height;
    switch (wrap_) {
        case WrapMode::Repeat:
            x = ((x % w) + w) % w;
            y = ((y % h) + h) % h;
            break;
        case WrapMode::Clamp:
            x = std::clamp(x, 0, w - 1);
            y = std::clamp(y, 0, h - 1);
            break;
        case WrapMode::Black:
            if (x < 0 || y < 0 || x >= w || y >= h) {
                out = Spectrum();
                return false;
            }
    }
    out = img_->get(x, y);
    return true;
}

Spectrum ImageLookup::evaluate(const TextureEvalContext& ctx) const {
    Vec2 st = map_.map(ctx);
    float s = st.x, t = 1 - st.y;
    if (!std::isfinite(s) || !std::isfinite(t)) return Spectrum();
    float x = s * img_->width - 0.5f, y = t * img_->height - 0.5f;
    // Keep coordinates in a range where int conversion is exact.
    if (std::fabs(x) > 1e8f || std::fabs(y) > 1e8f) return Spectrum();
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    float fx = x - x0, fy = y - y0;
    Spectrum a, b, c, d;
    texel(x0, y0, a);
    texel(x0 + 1, y0, b);
    texel(x0, y0 + 1, c);
    texel(x0 + 1, y0 + 1, d);
    Spectrum v = (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
    v *= scale_;
    if (invert_) v = Spectrum(1) - v;
    return clamp(v, 0, std::numeric_limits<float>::max());
}

std::shared_ptr<const Image> loadTextureImage(const std::string& path, ColorEncoding enc) {
    static std::mutex mutex;
    static std::map<std::pair<std::string, int>, std::shared_ptr<const Image>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto key = std::make_pair(path, int(enc));
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    auto img = std::make_shared<const Image>(readImage(path, enc));
    cache[key] = img;
    return img;
}

}  // namespace ps
