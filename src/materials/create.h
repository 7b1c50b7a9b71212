// Factories: materials and textures from the scene's parameter lists.
#pragma once
#include <map>
#include <memory>
#include <string>
#include "materials/material.h"
#include "scene/scene_description.h"

namespace ps {

struct TextureRegistry {
    std::map<std::string, std::shared_ptr<FloatTexture>> floats;
    std::map<std::string, std::shared_ptr<SpectrumTexture>> spectra;
};

// Unknown classes or parameters warn (and fall back to a sensible default);
// bad values throw InputError naming the parameter's location.
std::shared_ptr<FloatTexture> createFloatTexture(const TextureEntity& e, const TextureRegistry& reg,
                                                 const std::string& baseDirectory);
std::shared_ptr<SpectrumTexture> createSpectrumTexture(const TextureEntity& e, const TextureRegistry& reg,
                                                       const std::string& baseDirectory);
// A float parameter given as a constant (def when absent) or as `"texture name" "tex"`; an
// undefined texture throws InputError at the parameter.
std::shared_ptr<FloatTexture> floatTextureParam(const ParamSet& params, const std::string& name, float def,
                                                const TextureRegistry& reg);
// `named` holds the named materials created so far (mix refers to them). `spectralMode`
// (`--color spectral`) only silences what RGB mode alone lacks (dispersion).
std::shared_ptr<Material> createMaterial(const std::string& type, const ParamSet& params,
                                         const TextureRegistry& reg,
                                         const std::map<std::string, std::shared_ptr<Material>>& named,
                                         const std::string& baseDirectory, bool spectralMode = false);

}  // namespace ps
