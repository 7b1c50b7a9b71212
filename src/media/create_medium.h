// Media from MakeNamedMedium's parameters, with pbrt-v4's classes, parameter names and
// defaults (media.cpp: *Medium::Create). Bad parameters are InputErrors at the directive.
#pragma once
#include <memory>
#include "media/medium.h"
#include "scene/scene_description.h"

namespace ps {

std::unique_ptr<Medium> createMedium(const MediumEntity& e);

}  // namespace ps
