// pbrt-v4 scene files -> SceneDescription (PBRT-CONVENTIONS §1, §8).
#pragma once
#include <string>
#include "scene/scene_description.h"

namespace ps {

// Throws InputError naming file:line:column and the offending token. Include/Import paths,
// like every relative path in the scene, resolve against the main file's directory, which is
// stored as SceneDescription::baseDirectory (file-valued parameters are stored as written).
// Include/Import nest at most 64 files deep; cycles are reported.
SceneDescription parseSceneFile(const std::string& path);
SceneDescription parseSceneString(const std::string& text, const std::string& baseDirectory = ".",
                                  const std::string& displayName = "<string>");

}  // namespace ps
