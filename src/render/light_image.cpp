#include "render/light_image.h"

#include <cmath>

#include "materials/image_texture.h"
#include "util/path.h"

namespace ps {

std::shared_ptr<const Image> readLightImage(const SourceLoc& loc, const std::string& baseDirectory,
                                            const std::string& file, const std::string& what) {
    std::string path = resolvePath(baseDirectory, file);
    auto img = readNamedBy(loc, [&] { return loadTextureImage(path, ColorEncoding::SRGB); });
    for (float v : img->rgb)
        if (!std::isfinite(v))
            throw InputError(loc, what + " " + quoteForMessage(file) +
                                      ": the image has infinite or not-a-number values and cannot be a light");
    if (img->width <= 0 || img->height <= 0) throw InputError(loc, what + " " + quoteForMessage(file) + ": the image is empty");
    return img;
}

}  // namespace ps
