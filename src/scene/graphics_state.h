// The state that AttributeBegin saves and AttributeEnd restores (PBRT-CONVENTIONS §8 Blocks).
#pragma once
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include "math/transform.h"
#include "scene/scene_description.h"

namespace ps {

// Targets of the Attribute directive.
enum class AttributeTarget { Shape, Light, Material, Medium, Texture };
std::optional<AttributeTarget> attributeTarget(const std::string& name);

struct GraphicsState {
    // The CTM's two keyframes for motion blur (§1 Motion): ctm at TransformTimes' start, ctmEnd
    // at its end; transform directives change the ones ActiveTransform selects.
    Transform ctm, ctmEnd;
    bool reverseOrientation = false;
    MaterialRef material{0, ""};  // the default material is SceneDescription::materials[0]
    int areaLight = -1;
    MediumNames media;  // MediumInterface: the current inside and outside media
    bool startTransformActive = true, endTransformActive = true;
    // The directive (and where) that made the CTM singular or non-finite, for the error if
    // a shape is then placed under it.
    std::string singularSince;
    // The ColorSpace directive's space for RGB values parsed from here on (null: sRGB).
    const RGBColorSpace* colorSpace = nullptr;

    // Attribute defaults per target, shared between copies so that AttributeBegin is O(1)
    // however long the lists are; copied on write.
    std::array<std::shared_ptr<const std::vector<Param>>, 5> attributes;

    // Later Attribute statements override earlier ones of the same name.
    void addAttributes(AttributeTarget target, std::vector<Param> params);
    // Adds the defaults for `target` to ps (explicit parameters win); returns the number of
    // values copied, for the parser's resource budget.
    size_t applyAttributes(AttributeTarget target, ParamSet& ps) const;
};

}  // namespace ps
