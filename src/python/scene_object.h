// pathspace.Scene: a parsed scene file, built for rendering when first rendered (and again only
// when the colour mode changes); each render starts from the scene's own settings.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "render/scene.h"
#include "scene/ply_cache.h"
#include "scene/scene_description.h"

namespace ps::python {

class SceneObject {
public:
    SceneObject(SceneDescription desc, std::string file) : desc_(std::move(desc)), file_(std::move(file)) {}

    // The scene built in this colour mode, with the file's settings and pixels (a render's
    // options changed them on the last one). Throws InputError. Call without the GIL.
    Scene& prepare(bool spectral);
    const std::string& file() const { return file_; }  // as given to load(), or "<string>"

    // Overrides of the scene file: each changes the description, and the next render builds
    // the scene again from it, its meshes from memory. Throw InputError for a bad value.
    void setResolution(int width, int height);
    void setCamera(Vec3 eye, Vec3 target, Vec3 up);  // as LookAt, the camera's whole transform
    void setMaterialParam(const std::string& material, Param param);
    void setLightScale(size_t index, float scale);  // LightSource directives, then AreaLightSource ones
    std::vector<std::string> lights() const;        // what each index names

private:
    SceneDescription desc_;
    std::string file_;
    PlyCache meshes_;
    std::unique_ptr<Scene> built_;
    bool builtSpectral_ = false;
    RenderSettings settings_;  // built_'s own, before any option
    PixelBounds bounds_;
};

}  // namespace ps::python
