// pbrt-v4 scene files -> SceneDescription (PBRT-CONVENTIONS §1, §8).
#pragma once
#include <string>
#include "scene/scene_description.h"

namespace ps {

// Throws InputError naming file:line:column and the offending token.
SceneDescription parseSceneFile(const std::string& path);
SceneDescription parseSceneString(const std::string& text, const std::string& baseDirectory = ".",
                                  const std::string& displayName = "<string>");

}  // namespace ps
