// Texture classes: constant, scale, mix and checkerboard, for float and spectrum values,
// with pbrt-v4's uv mapping (s = uscale*u + udelta, t = vscale*v + vdelta). Image maps are
// in image_texture.h.
#pragma once
#include <cmath>
#include <memory>
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

// tex1 where floor(s) + floor(t) is even, tex2 elsewhere. Known difference: pbrt-v4 blends
// the two near edges with a box-filtered checkerboard whose width comes from ray
// differentials; this is the point-sampled (unfiltered) checkerboard that pbrt renders
// with "disabletexturefiltering".
template <typename T>
class CheckerboardTexture final : public TextureOf<T>::type {
public:
    CheckerboardTexture(UVMapping m, std::shared_ptr<typename TextureOf<T>::type> a, std::shared_ptr<typename TextureOf<T>::type> b)
        : map_(m), a_(std::move(a)), b_(std::move(b)) {}
    T evaluate(const TextureEvalContext& ctx) const override {
        Vec2 st = map_.map(ctx);
        return oddCell(st.x) == oddCell(st.y) ? a_->evaluate(ctx) : b_->evaluate(ctx);
    }

private:
    // Whether floor(v) is odd, without integer overflow for huge coordinates (NaN: odd).
    static bool oddCell(float v) {
        float c = std::floor(v);
        return !(c - 2 * std::floor(c * 0.5f) == 0);
    }
    UVMapping map_;
    std::shared_ptr<typename TextureOf<T>::type> a_, b_;
};

}  // namespace ps
