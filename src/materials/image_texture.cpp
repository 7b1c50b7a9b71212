#include "materials/image_texture.h"

#include <filesystem>
#include <limits>
#include <map>
#include <mutex>

#include "util/path.h"

namespace ps {

int ImageLookup::wrap(int i, int n) const {
    switch (wrap_) {
        case WrapMode::Repeat: return ((i % n) + n) % n;
        case WrapMode::Clamp: return std::clamp(i, 0, n - 1);
        case WrapMode::Black: return i >= 0 && i < n ? i : -1;
    }
    return -1;
}

Spectrum ImageLookup::texel(int x, int y) const {
    // Already wrapped; -1: outside a black-bordered image.
    if (x < 0 || y < 0) return {};
    const int w = img_->width;
    switch (channels_) {
        case ImageChannels::RGB: return img_->get(x, y);
        case ImageChannels::Average: return Spectrum(img_->get(x, y).average());
        case ImageChannels::Alpha: return Spectrum(img_->alpha[size_t(y) * w + x]);
    }
    return {};
}

Spectrum ImageLookup::bilinear(Vec2 st) const {
    // Continuous texel coordinates: texel centres sit at half-integers.
    float x = st.x * img_->width - 0.5f, y = (1 - st.y) * img_->height - 0.5f;
    // Non-finite or absurd coordinates (beyond exact int conversion) read as black.
    if (!(std::fabs(x) < 1e8f) || !(std::fabs(y) < 1e8f)) return {};
    const int xi = int(std::floor(x)), yi = int(std::floor(y));
    const float fx = x - xi, fy = y - yi;
    // Each axis wrapped once (the modulo per texel cost more than the lookups).
    const int w = img_->width, h = img_->height;
    const int x0 = wrap(xi, w), y0 = wrap(yi, h);
    const int x1 = wrap_ == WrapMode::Repeat ? (x0 + 1 == w ? 0 : x0 + 1) : wrap(xi + 1, w);
    const int y1 = wrap_ == WrapMode::Repeat ? (y0 + 1 == h ? 0 : y0 + 1) : wrap(yi + 1, h);
    return (texel(x0, y0) * (1 - fx) + texel(x1, y0) * fx) * (1 - fy) +
           (texel(x0, y1) * (1 - fx) + texel(x1, y1) * fx) * fy;
}

Spectrum ImageLookup::evaluate(const TextureEvalContext& ctx) const {
    Spectrum v = bilinear(map_.map(ctx));
    v *= scale_;
    if (invert_) v = Spectrum(1) - v;
    return clamp(v, 0, std::numeric_limits<float>::max());
}

bool hasNonOpaqueAlpha(const Image& img) {
    for (float a : img.alpha)
        if (a != 1) return true;
    return false;
}

std::shared_ptr<const Image> loadTextureImage(const std::string& path, ColorEncoding enc) {
    static std::mutex mutex;
    static std::map<std::pair<std::string, int>, std::shared_ptr<const Image>> cache;
    if (lowerExtension(path) != ".png") enc = ColorEncoding::SRGB;  // ignored by the reader
    std::error_code ec;
    std::filesystem::path abs = std::filesystem::absolute(path, ec);
    auto key = std::make_pair(ec ? path : abs.lexically_normal().string(), int(enc));
    // Held while reading, so concurrent first uses of one file read it once.
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    auto img = std::make_shared<const Image>(readImage(path, enc));
    cache.emplace(key, img);
    return img;
}

}  // namespace ps
