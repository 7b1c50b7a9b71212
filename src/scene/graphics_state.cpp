#include "scene/graphics_state.h"

#include <algorithm>

namespace ps {

std::optional<AttributeTarget> attributeTarget(const std::string& name) {
    if (name == "shape") return AttributeTarget::Shape;
    if (name == "light") return AttributeTarget::Light;
    if (name == "material") return AttributeTarget::Material;
    if (name == "medium") return AttributeTarget::Medium;
    if (name == "texture") return AttributeTarget::Texture;
    return std::nullopt;
}

void GraphicsState::addAttributes(AttributeTarget target, std::vector<Param> params) {
    auto& slot = attributes[size_t(target)];
    auto list = slot ? std::make_shared<std::vector<Param>>(*slot) : std::make_shared<std::vector<Param>>();
    for (Param& p : params) {
        p.fromAttribute = true;  // defaults need not be used (pbrt: mayBeUnused)
        auto it = std::find_if(list->begin(), list->end(), [&](const Param& q) { return q.name == p.name; });
        if (it != list->end()) *it = std::move(p);
        else list->push_back(std::move(p));
    }
    slot = std::move(list);
}

size_t GraphicsState::applyAttributes(AttributeTarget target, ParamSet& ps) const {
    const auto& slot = attributes[size_t(target)];
    if (!slot) return 0;
    size_t copied = 0;
    for (const Param& p : *slot) {
        if (ps.has(p.name)) continue;
        copied += p.numbers.size() + p.strings.size() + p.bools.size();
        ps.addDefault(p);
    }
    return copied;
}

}  // namespace ps
