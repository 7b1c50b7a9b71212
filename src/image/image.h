// RGB float images: reading textures and environment maps, writing renders.
#pragma once
#include <string>
#include <vector>
#include "math/spectrum.h"

namespace ps {

// How 8-bit PNG values are decoded (PBRT-CONVENTIONS §6: only PNG honours this;
// TGA/JPEG/BMP are always sRGB-decoded, EXR/HDR/PFM are always linear).
enum class ColorEncoding { SRGB, Linear };

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 floats per pixel, row 0 = top, linear
    std::vector<float> alpha;  // empty unless the file has an alpha channel
    // A crop of a larger film: the film's size and the crop's top-left pixel in it (EXR keeps
    // them as the display and data windows, as pbrt-v4 writes a crop). 0: not a crop.
    int filmWidth = 0, filmHeight = 0, x0 = 0, y0 = 0;

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(size_t(w) * h * 3, 0.0f) {}
    Spectrum get(int x, int y) const {
        const float* p = &rgb[(size_t(y) * width + x) * 3];
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, const Spectrum& s) {
        float* p = &rgb[(size_t(y) * width + x) * 3];
        p[0] = s.r; p[1] = s.g; p[2] = s.b;
    }
};

// Reads PNG, JPEG, TGA, BMP, HDR, EXR and PFM. Throws InputError naming the file and
// what is wrong (missing, unreadable, not an image, unsupported layout).
Image readImage(const std::string& path, ColorEncoding pngEncoding = ColorEncoding::SRGB);

// Writes by extension: .exr (float32), .pfm, .png (sRGB-encoded, clamped to [0,1]).
// Writes to a temporary file in the same directory and renames it over the target, so a
// failure never leaves a partial file or destroys an older one. Throws InputError for an
// unknown extension or an unwritable location.
void writeImage(const std::string& path, const Image& image);

// True when the extension is one writeImage supports.
bool isWritableImageExtension(const std::string& path);

// sRGB transfer functions.
float srgbToLinear(float v);
float linearToSrgb(float v);

}  // namespace ps
