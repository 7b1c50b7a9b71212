// Texture classes: constant, scale, mix and checkerboard, for float and spectrum values.
// Image maps are in image_texture.h, the other procedural classes in procedural_textures.h,
// the mappings from the surface to texture coordinates in texture_mapping.h.
#pragma once
#include <cmath>
#include <memory>
#include "materials/texture.h"
#include "materials/texture_mapping.h"

namespace ps {

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
    T value() const { return v_; }

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

// tex1 where floor(s) + floor(t) is even, tex2 elsewhere; in 3-D ("dimension" 3), tex1 where
// floor(x) + floor(y) + floor(z) of the texture-space point is even. Known difference:
// pbrt-v4 blends the two near edges with a box-filtered checkerboard whose width comes from
// ray differentials; this is the point-sampled (unfiltered) checkerboard that pbrt renders
// with "disabletexturefiltering".
template <typename T>
class CheckerboardTexture final : public TextureOf<T>::type {
public:
    using Tex = std::shared_ptr<typename TextureOf<T>::type>;
    CheckerboardTexture(TextureMapping2D m, Tex a, Tex b) : map2_(m), a_(std::move(a)), b_(std::move(b)) {}
    CheckerboardTexture(TextureMapping3D m, Tex a, Tex b) : map3_(m), solid_(true), a_(std::move(a)), b_(std::move(b)) {}
    T evaluate(const TextureEvalContext& ctx) const override {
        bool odd;
        if (solid_) {
            Vec3 q = map3_.map(ctx);
            odd = oddCell(q.x) != (oddCell(q.y) != oddCell(q.z));
        } else {
            Vec2 st = map2_.map(ctx);
            odd = oddCell(st.x) != oddCell(st.y);
        }
        return odd ? b_->evaluate(ctx) : a_->evaluate(ctx);
    }

private:
    // Whether floor(v) is odd, without integer overflow for huge coordinates (NaN: odd).
    static bool oddCell(float v) {
        float c = std::floor(v);
        return !(c - 2 * std::floor(c * 0.5f) == 0);
    }
    TextureMapping2D map2_;
    TextureMapping3D map3_;
    bool solid_ = false;
    Tex a_, b_;
};

}  // namespace ps
