// Spectrum textures in spectral mode (math/spectrum.h): a constant parameter keeps the
// spectrum it was given and is evaluated at the path's wavelengths; any other texture is
// evaluated in RGB and lifted per lookup by the use it feeds, as pbrt-v4 lifts the RGB of its
// image textures. In RGB mode both return the RGB value.
#pragma once
#include <memory>
#include <optional>

#include "materials/texture.h"
#include "materials/textures.h"
#include "scene/params.h"
#include "spectral/sampled_spectrum.h"

namespace ps {

class SpectralConstantTexture final : public SpectrumTexture {
public:
    SpectralConstantTexture(Spectrum rgb, SpectrumSource spectrum) : rgb_(rgb), spectrum_(std::move(spectrum)) {}
    Spectrum evaluate(const TextureEvalContext& ctx) const override {
        return ctx.lambda ? sampleSpectrum(spectrum_, *ctx.lambda) : rgb_;
    }
    const Spectrum& rgb() const { return rgb_; }

private:
    Spectrum rgb_;
    SpectrumSource spectrum_;
};

// A texture of the scene's Texture directives, whose values are RGB of the rendering space
// (linear sRGB), used as `kind`. Limitation: constants inside it given as named spectra or
// blackbody reach spectral mode through their RGB.
class LiftedSpectrumTexture final : public SpectrumTexture {
public:
    LiftedSpectrumTexture(std::shared_ptr<SpectrumTexture> rgb, SpectrumKind kind) : rgb_(std::move(rgb)), kind_(kind) {}
    Spectrum evaluate(const TextureEvalContext& ctx) const override {
        if (!ctx.lambda) return rgb_->evaluate(ctx);
        TextureEvalContext rgbCtx = ctx;
        rgbCtx.lambda = nullptr;
        const Spectrum v = rgb_->evaluate(rgbCtx);
        switch (kind_) {
            case SpectrumKind::Albedo: return liftAlbedo(v, *ctx.lambda);
            case SpectrumKind::Unbounded: return liftUnbounded(v, *ctx.lambda);
            default: return liftIlluminant(v, *ctx.lambda);
        }
    }

    const SpectrumTexture& rgbTexture() const { return *rgb_; }

private:
    std::shared_ptr<SpectrumTexture> rgb_;
    SpectrumKind kind_;
};

// The RGB value of a texture that is the same everywhere (RGB mode's prebuilt BxDFs), or
// nullopt.
inline std::optional<Spectrum> constantRGB(const SpectrumTexture& t) {
    if (auto* c = dynamic_cast<const SpectralConstantTexture*>(&t)) return c->rgb();
    if (auto* c = dynamic_cast<const ConstantTexture<Spectrum>*>(&t)) return c->value();
    if (auto* l = dynamic_cast<const LiftedSpectrumTexture*>(&t)) return constantRGB(l->rgbTexture());
    return std::nullopt;
}

}  // namespace ps
