// Turns a parsed SceneDescription into a renderable Scene.
#pragma once
#include <memory>
#include "render/scene.h"
#include "scene/scene_description.h"
#include "util/path.h"

namespace ps {

struct TextureRegistry;

// Throws InputError for problems in the scene (missing files, bad values); warns for
// unsupported features and falls back to the nearest supported behaviour. `spectral` is the
// colour mode (`--color spectral`), known while building so that warnings about what RGB
// mode lacks are given only in RGB mode.
std::unique_ptr<Scene> buildScene(const SceneDescription& desc, bool spectral = false);

// Individual steps, exposed for the builder's own files and for tests.
// `textures` resolves a "texture alpha".
std::unique_ptr<Shape> createShape(const ShapeEntity& e, const Transform& toScene, const std::string& baseDirectory,
                                   const TextureRegistry& textures);
// Lights declared by LightSource (not area lights).
std::unique_ptr<Light> createLight(const LightEntity& e, const std::string& baseDirectory);
// Camera, film, filter, sampler and integrator settings.
void applyRenderOptions(const SceneDescription& desc, Scene& scene);

}  // namespace ps
