// pbrt-v4's "diffuse" area light with "filename": the emitted radiance is an RGB image over
// the emitter's (u, v), looked up bilinearly at (u, 1 - v) (image row 0 is the top, so v = 1
// is the top row), clamped at the image's edges, negative values read as 0, times scale.
#pragma once
#include <limits>
#include <memory>
#include "materials/image_texture.h"

namespace ps {

class EmissionImage {
public:
    explicit EmissionImage(std::shared_ptr<const Image> img)
        : lookup_(img, TextureMapping2D(), WrapMode::Clamp, 1, false, ImageChannels::RGB) {
        Spectrum sum;
        double lum = 0;
        for (int y = 0; y < img->height; ++y)
            for (int x = 0; x < img->width; ++x) {
                sum += clamp(img->get(x, y), 0, std::numeric_limits<float>::max());
                lum += img->get(x, y).luminance();
            }
        float n = float(img->width) * float(img->height);
        mean_ = sum / n;
        meanLuminance_ = float(lum / n);
    }
    Spectrum at(Vec2 uv) const { return clamp(lookup_.bilinear(uv), 0, std::numeric_limits<float>::max()); }
    // Mean over texels of the RGB values (negatives as 0): the emitter's mean radiance.
    Spectrum mean() const { return mean_; }
    // Mean luminance of the raw values, which pbrt-v4's "power" normalisation divides by.
    float meanLuminance() const { return meanLuminance_; }

private:
    ImageLookup lookup_;
    Spectrum mean_;
    float meanLuminance_ = 0;
};

}  // namespace ps
