// pbrt-v4's "imagemap" textures: bilinear lookups at (s, 1 - t) of an image read once per
// process (image row 0 is the top, so uv (0,0) is the bottom-left corner of the picture).
//
// Known differences from pbrt-v4 (PBRT-CONVENTIONS §6): pbrt resamples non-power-of-two
// images up to powers of two and picks a MIP level from ray differentials even for
// "bilinear"; this looks up the original image at full resolution, which matches pbrt run
// with "disabletexturefiltering" on power-of-two images. "trilinear"/"ewa"/"point" filters
// are treated as bilinear.
#pragma once
#include <memory>
#include <string>
#include "image/image.h"
#include "materials/textures.h"

namespace ps {

enum class WrapMode { Repeat, Clamp, Black };

// Which values a lookup returns: RGB for spectrum textures; for float textures the mean of
// R, G, B, or alpha when the image has an alpha channel that is not all ones (as pbrt).
enum class ImageChannels { RGB, Average, Alpha };

class ImageLookup {
public:
    ImageLookup(std::shared_ptr<const Image> img, TextureMapping2D m, WrapMode w, float scale, bool invert, ImageChannels c)
        : img_(std::move(img)), map_(m), wrap_(w), scale_(scale), invert_(invert), channels_(c) {}
    // scale * bilinear lookup, then 1 - value if inverted, clamped to >= 0.
    Spectrum evaluate(const TextureEvalContext& ctx) const;
    // The bilinear interpolation alone at texture coordinates st, looked up at (s, 1 - t);
    // black for non-finite or absurd coordinates.
    Spectrum bilinear(Vec2 st) const;

private:
    Spectrum texel(int x, int y) const;  // x, y wrapped; -1: black
    int wrap(int i, int n) const;         // by the wrap mode; -1: outside a black border
    std::shared_ptr<const Image> img_;
    TextureMapping2D map_;
    WrapMode wrap_;
    float scale_;
    bool invert_;
    ImageChannels channels_;
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
    // The lookup must use ImageChannels::Average or Alpha (all three components equal).
    explicit FloatImageTexture(ImageLookup l) : lookup_(std::move(l)) {}
    float evaluate(const TextureEvalContext& ctx) const override { return lookup_.evaluate(ctx).r; }

private:
    ImageLookup lookup_;
};

// The image at path, read on first use and shared afterwards (thread-safe). Only PNG files
// honour the encoding, so other formats share one entry whatever encoding is asked for.
std::shared_ptr<const Image> loadTextureImage(const std::string& path, ColorEncoding pngEncoding);

// True when the image has alpha values other than 1 (float lookups then return alpha).
bool hasNonOpaqueAlpha(const Image& img);

}  // namespace ps
