// pbrt-v4's procedural texture classes beyond constant/scale/mix/checkerboard (textures.h):
// directionmix, dots, bilerp, and the noise textures fbm, wrinkled, windy and marble, with
// pbrt-v4's definitions, point-sampled (PBRT-CONVENTIONS §6; see texture_mapping.h).
#pragma once
#include <memory>
#include "materials/noise.h"
#include "materials/texture_mapping.h"
#include "materials/textures.h"

namespace ps {

// amount * tex1 + (1 - amount) * tex2 with amount = |dot(n, dir)|, n the geometric normal and
// dir a unit world-space direction (the "dir" parameter through the texture's CTM).
template <typename T>
class DirectionMixTexture final : public TextureOf<T>::type {
public:
    using Tex = std::shared_ptr<typename TextureOf<T>::type>;
    DirectionMixTexture(Tex a, Tex b, Vec3 dir) : a_(std::move(a)), b_(std::move(b)), dir_(dir) {}
    T evaluate(const TextureEvalContext& ctx) const override {
        float t = absDot(ctx.n, dir_);
        T va = t != 0 ? a_->evaluate(ctx) : T(0);
        T vb = t != 1 ? b_->evaluate(ctx) : T(0);
        return va * t + vb * (1 - t);
    }

private:
    Tex a_, b_;
    Vec3 dir_;
};

// Whether (s, t) lies in a polka dot: the unit cell around the nearest integer point holds a
// dot of radius 0.35 where the noise at its centre is positive, shifted by up to 0.15 by two
// more noise values (pbrt-v4's InsidePolkaDot).
bool insidePolkaDot(Vec2 st);

template <typename T>
class DotsTexture final : public TextureOf<T>::type {
public:
    using Tex = std::shared_ptr<typename TextureOf<T>::type>;
    DotsTexture(TextureMapping2D m, Tex inDot, Tex outOfDot) : map_(m), in_(std::move(inDot)), out_(std::move(outOfDot)) {}
    T evaluate(const TextureEvalContext& ctx) const override {
        return insidePolkaDot(map_.map(ctx)) ? in_->evaluate(ctx) : out_->evaluate(ctx);
    }

private:
    TextureMapping2D map_;
    Tex in_, out_;
};

// Bilinear interpolation of four corner values over (s, t): v00 at (0,0), v10 at (1,0),
// v01 at (0,1), v11 at (1,1), extrapolated outside the unit square.
template <typename T>
class BilerpTexture final : public TextureOf<T>::type {
public:
    BilerpTexture(TextureMapping2D m, T v00, T v01, T v10, T v11) : map_(m), v00_(v00), v01_(v01), v10_(v10), v11_(v11) {}
    T evaluate(const TextureEvalContext& ctx) const override {
        Vec2 st = map_.map(ctx);
        const float s = st.x, t = st.y;
        return v00_ * ((1 - s) * (1 - t)) + v10_ * (s * (1 - t)) + v01_ * ((1 - s) * t) + v11_ * (s * t);
    }

private:
    TextureMapping2D map_;
    T v00_, v01_, v10_, v11_;
};

// A sum of noise octaves, Sum(q, roughness, octaves), at the texture-space point q: fbm
// ("fbm") or turbulence ("wrinkled").
template <float (*Sum)(Vec3, float, int)>
class OctaveNoiseTexture final : public FloatTexture {
public:
    OctaveNoiseTexture(TextureMapping3D m, int octaves, float omega) : map_(m), octaves_(octaves), omega_(omega) {}
    float evaluate(const TextureEvalContext& ctx) const override { return Sum(map_.map(ctx), omega_, octaves_); }

private:
    TextureMapping3D map_;
    int octaves_;
    float omega_;
};
using FBmTexture = OctaveNoiseTexture<fbm>;
using WrinkledTexture = OctaveNoiseTexture<turbulence>;

// Waves: |fbm(q / 10, 0.5, 3)| (the wind's strength) times fbm(q, 0.5, 6) (the wave height).
class WindyTexture final : public FloatTexture {
public:
    explicit WindyTexture(TextureMapping3D m) : map_(m) {}
    float evaluate(const TextureEvalContext& ctx) const override;

private:
    TextureMapping3D map_;
};

// Marble veins: a fixed colour spline (piecewise cubic Bezier through nine grey-blue control
// colours, times 1.5) at 0.5 + 0.5 sin(q.y + variation fbm(q, roughness, octaves)), q the
// texture-space point times scale.
class MarbleTexture final : public SpectrumTexture {
public:
    MarbleTexture(TextureMapping3D m, int octaves, float omega, float scale, float variation)
        : map_(m), octaves_(octaves), omega_(omega), scale_(scale), variation_(variation) {}
    Spectrum evaluate(const TextureEvalContext& ctx) const override;

private:
    TextureMapping3D map_;
    int octaves_;
    float omega_, scale_, variation_;
};

}  // namespace ps
