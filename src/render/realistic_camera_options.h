// Camera "realistic": its parameters and lens description file -> the camera's lens system.
#pragma once
#include <memory>
#include <string>
#include "camera/lens_system.h"
#include "scene/params.h"
#include "util/error.h"

namespace ps {

// pbrt-v4's parameters: "lensfile" (required, relative to the scene's directory),
// "aperturediameter" (mm, default 1), "focusdistance" (scene units from the film, default
// 10), "aperture" (a built-in shape name or an image file). Throws InputError located at
// the Camera directive (or the parameter) for a missing or malformed lens file, an unknown
// aperture image, or a lens that cannot focus there.
std::shared_ptr<const LensSystem> createLensSystem(const ParamSet& ps, const SourceLoc& cameraLoc,
                                                   const std::string& baseDirectory, float filmDiagonalMm, int xRes,
                                                   int yRes);

}  // namespace ps
