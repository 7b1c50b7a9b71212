// Texture classes: constant, scale, mix, checkerboard and image maps, for float and
// spectrum values, with pbrt-v4's uv mapping (s = uscale*u + udelta, t = vscale*v + vdelta).
#pragma once
#include <memory>
#include "image/image.h"
#include "materials/texture.h"

namespace ps {

struct UVMapping {
    float su = 1, sv = 1, du = 0, dv = 0;
    Vec2 map(const TextureEvalContext& ctx) const { return {su * ctx.uv.x + du, sv * ctx.uv.y + dv}; }
};

template <typename T>
struct TextureOf;
template <>
struct TextureOf<float> { using type = FloatTexture; };
template <>
struct TextureOf<Spectrum> { using type = SpectrumTexture; };

template <typename T>
class ConstantTexture final : public TextureOf<T>::type {
public:
    explicit ConstantTexture(T v) : v_(v) {}
    T evaluate(const TextureEvalContext&) const override { return v_; }

private:
    T v_;
};

template <typename T>
class ScaleTexture final : public TextureOf<T>::type {
public:
    ScaleTexture(std::shared_ptr<typename TextureOf<T>::type> tex, std::shared_ptr<FloatTexture> scale)
        : tex_(std::move(tex)), scale_(std::move(scale)) {}
    T evaluate(const TextureEvalContext& ctx) const override {
        float s = scale_->evaluate(ctx);
        return s == 0 ? T(0) : tex_->evaluate(ctx) * s;
    }

private:
    std::shared_ptr<typename TextureOf<T>::type> tex_;
    std::shared_ptr<FloatTexture> scale_;
};

// (1 - amount) * tex1 + amount * tex2.
template <typename T>
class MixTexture final : public TextureOf<T>::type {
public:
    MixTexture(std::shared_ptr<typename TextureOf<T>::type> a, std::shared_ptr<typename TextureOf<T>::type> b,
               std::shared_ptr<FloatTexture> amount)
        : a_(std::move(a)), b_(std::move(b)), amount_(std::move(amount)) {}
    T evaluate(const TextureEvalContext& ctx) const override {
        float t = amount_->evaluate(ctx);
        T va = t != 1 ? a_->evaluate(ctx) : T(0);
        T vb = t != 0 ? b_->evaluate(ctx) : T(0);
        return va * (1 - t) + vb * t;
    }

private:
    std::shared_ptr<typename TextureOf<T>::type> a_, b_;
    std::shared_ptr<FloatTexture> amount_;
};

// tex1 where floor(s) + floor(t) is even, tex2 elsewhere (no antialiasing).
template <typename T>
class CheckerboardTexture final : public TextureOf<T>::type {
public:
    CheckerboardTexture(UVMapping m, std::shared_ptr<typename TextureOf<T>::type> a, std::shared_ptr<typename TextureOf<T>::type> b)
        : map_(m), a_(std::move(a)), b_(std::move(b)) {}
    T evaluate(const TextureEvalContext& ctx) const override {
        Vec2 st = map_.map(ctx);
        long long parity = (long long)std::floor(st.x) + (long long)std::floor(st.y);
        return (parity & 1) == 0 ? a_->evaluate(ctx) : b_->evaluate(ctx);
    }

private:
    UVMapping map_;
    std::shared_ptr<typename TextureOf<T>::type> a_, b_;
};

enum class WrapMode { Repeat, Clamp, Black };

// Bilinear lookup at (s, 1 - t): image row 0 is the top, uv (0,0) the bottom-left corner.
// pbrt-v4 would pick a MIP level from ray differentials; this looks up the full resolution.
class ImageLookup {
public:
    ImageLookup(std::shared_ptr<const Image> img, UVMapping m, WrapMode w, float scale, bool invert)
        : img_(std::move(img)), map_(m), wrap_(w), scale_(scale), invert_(invert) {}
    Spectrum evaluate(const TextureEvalContext& ctx) const;

private:
    bool texel(int x, int y, Spectrum& out) const;
    std::shared_ptr<const Image> img_;
    UVMapping map_;
    WrapMode wrap_;
    float scale_;
    bool invert_;
};

class SpectrumImageTexture final : public SpectrumTexture {
public:
    explicit SpectrumImageTexture(ImageLookup l) : lookup_(std::move(l)) {}
    Spectrum evaluate(const TextureEvalContext& ctx) const override { return lookup_.evaluate(ctx); }

private:
    ImageLookup lookup_;
};

class FloatImageTexture final : public FloatTexture {
public:
    explicit FloatImageTexture(ImageLookup l) : lookup_(std::move(l)) {}
    float evaluate(const TextureEvalContext& ctx) const override { return lookup_.evaluate(ctx).average(); }

private:
    ImageLookup lookup_;
};

// Each image file is read once per process, whichever textures use it.
std::shared_ptr<const Image> loadTextureImage(const std::string& path, ColorEncoding pngEncoding);

}  // namespace ps
