#include "python/scene_object.h"

#include "render/scene_builder.h"
#include "util/error.h"

namespace ps::python {

Scene& SceneObject::prepare(bool spectral) {
    if (!built_ || builtSpectral_ != spectral) {
        built_.reset();  // one built scene at a time: its meshes may be large
        const HeldWarnings inFileOrder;
        const PlyCache::Use cached(meshes_);
        built_ = buildScene(desc_, spectral);
        builtSpectral_ = spectral;
        settings_ = built_->settings();
        bounds_ = built_->pixelBounds();
    } else {
        built_->settings() = settings_;
        built_->setPixelBounds(bounds_);
    }
    return *built_;
}

namespace {

Param number(const std::string& typeName, const std::string& name, std::vector<double> values) {
    Param p;
    p.type = typeName == "integer" ? ParamType::Integer : ParamType::Float;
    p.typeName = typeName;
    p.name = name;
    p.numbers = std::move(values);
    return p;
}

}  // namespace

void SceneObject::setResolution(int width, int height) {
    if (width <= 0 || height <= 0)
        throw InputError("set_resolution: the width and height must be positive, not " + std::to_string(width) + " x " +
                         std::to_string(height));
    desc_.film.params.add(number("integer", "xresolution", {double(width)}));
    desc_.film.params.add(number("integer", "yresolution", {double(height)}));
    built_.reset();
}

void SceneObject::setCamera(Vec3 eye, Vec3 target, Vec3 up) {
    const std::optional<Transform> worldFromCamera = Transform::lookAt(eye, target, up);
    if (!worldFromCamera)
        throw InputError("set_camera: the position and look-at point must differ and the up vector must not be "
                         "parallel to the view direction");
    desc_.camera.worldFromCamera = desc_.camera.worldFromCameraEnd = *worldFromCamera;
    built_.reset();
}

void SceneObject::setMaterialParam(const std::string& material, Param param) {
    auto it = desc_.namedMaterials.find(material);
    if (it == desc_.namedMaterials.end()) {
        std::string known;
        for (const auto& [name, _] : desc_.namedMaterials) known += (known.empty() ? "\"" : ", \"") + name + "\"";
        throw InputError("set_material: the scene has no material named \"" + material + "\" (its named materials: " +
                         (known.empty() ? "none" : known) + ")");
    }
    param.loc = it->second.loc;  // an error in the value is reported at the material's directive
    it->second.params.add(std::move(param));
    built_.reset();
}

void SceneObject::setLightScale(size_t index, float scale) {
    const size_t n = desc_.lights.size() + desc_.areaLights.size();
    if (index >= n)
        throw InputError("set_light_scale: light " + std::to_string(index) + " of " + std::to_string(n) +
                         " (Scene.lights lists them)");
    SceneEntity& light = index < desc_.lights.size() ? desc_.lights[index] : desc_.areaLights[index - desc_.lights.size()];
    light.params.add(number("float", "scale", {double(scale)}));
    built_.reset();
}

std::vector<std::string> SceneObject::lights() const {
    std::vector<std::string> v;
    for (const LightEntity& l : desc_.lights) v.push_back("LightSource \"" + l.type + "\" at " + l.loc.str());
    for (const SceneEntity& l : desc_.areaLights) v.push_back("AreaLightSource \"" + l.type + "\" at " + l.loc.str());
    return v;
}

}  // namespace ps::python
