// writeImage: picks the encoder by extension, guards against non-finite values and
// inconsistent images, and leaves the disk to the atomic writer.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "image/image_formats.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/path.h"

namespace ps {

namespace imageio {

float finiteForOutput(float v) {
    if (std::isnan(v)) return 0.0f;
    if (std::isinf(v)) return std::copysign(std::numeric_limits<float>::max(), v);
    return v;
}

}  // namespace imageio

bool isWritableImageExtension(const std::string& path) {
    std::string ext = lowerExtension(path);
    return ext == ".exr" || ext == ".pfm" || ext == ".png";
}

void writeImage(const std::string& path, const Image& image) {
    const std::string what = path + ": cannot write image: ";
    std::string ext = lowerExtension(path);
    if (!isWritableImageExtension(path))
        throw InputError(what + "unsupported extension \"" + ext + "\" (supported: .exr, .pfm, .png)");
    // A malformed Image is a caller bug, but must not turn into an out-of-bounds read.
    if (image.width <= 0 || image.height <= 0 || image.width > imageio::kMaxPixels / image.height ||
        image.rgb.size() != size_t(image.width) * size_t(image.height) * 3)
        throw InputError(what + "invalid image (" + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " with " + std::to_string(image.rgb.size()) + " values)");

    std::vector<char> bytes;
    try {
        if (ext == ".exr") bytes = imageio::encodeExr(image);
        else if (ext == ".pfm") bytes = imageio::encodePfm(image);
        else bytes = imageio::encodePng(image);
    } catch (const std::exception& e) {  // OpenEXR exceptions, bad_alloc
        throw InputError(what + e.what());
    }
    writeFileAtomically(path, {std::span<const char>(bytes)}, "image");
}

}  // namespace ps
