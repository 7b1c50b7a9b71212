// Images that lights read (goniometric, projection, area-light emission): the file named by
// a light's "filename", resolved against the scene's directory, read once per process and
// rejected, as pbrt-v4 rejects it, when a texel is infinite or not a number.
#pragma once
#include <memory>
#include <string>
#include "image/image.h"
#include "util/error.h"

namespace ps {

// what: the light, for messages ("goniometric light"). Throws InputError located at loc.
std::shared_ptr<const Image> readLightImage(const SourceLoc& loc, const std::string& baseDirectory,
                                            const std::string& file, const std::string& what);

}  // namespace ps
