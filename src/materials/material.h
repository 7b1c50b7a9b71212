// Materials turn textures at a shading point into a BxDF. The BxDF is built in the
// caller's ScratchBuffer (no heap traffic in the render loop).
#pragma once
#include <memory>
#include <string>
#include "geometry/fibre_kind.h"
#include "materials/bxdf.h"
#include "materials/texture.h"
#include "util/scratch.h"

namespace ps {

class ShadingDetail;  // materials/shading_detail.h

struct MaterialEvalContext : TextureEvalContext {
    Vec3 wo;     // world-space direction towards the previous vertex
    Vec3 dpdu;   // world-space tangent along u (anisotropic frames follow it)
    FibreKind fibre = FibreKind::None;
};

class Material {
public:
    virtual ~Material() = default;
    // nullptr for `interface` (no scattering: the ray passes through, not a bounce).
    virtual const BxDF* bxdf(const MaterialEvalContext& ctx, ScratchBuffer& scratch) const = 0;
    // `mix` resolves to one of its members; everything else returns itself.
    virtual const Material* resolve(const MaterialEvalContext& ctx) const { (void)ctx; return this; }
    virtual bool isInterface() const { return false; }
    // Whether its BxDF's f and pdf are stochastic estimates (layered materials, whose pdf
    // only approximates how they sample): fine for estimators and MIS, not for the exact
    // transition densities of path-space mutations.
    virtual bool stochasticBxDF() const { return false; }
    // The BxDF when it is the same at every point (all textures constant), built once, so
    // the render loop neither evaluates textures nor builds one per hit; null otherwise.
    const BxDF* constantBxDF() const { return constant_.get(); }
    // pbrt-v4's "normalmap" or "displacement" (bump map) of this material, or null.
    const ShadingDetail* shadingDetail() const { return detail_.get(); }
    void setShadingDetail(std::shared_ptr<const ShadingDetail> d) {
        detail_ = std::move(d);
        needsDerivatives_ = needsDerivatives_ || detail_;
    }
    // True when hits need the shading derivatives a map reads (SurfaceInteraction::dpdv ...):
    // this material, or for `mix` one of its members, has a map.
    bool needsShadingDerivatives() const { return needsDerivatives_; }
    // Its scene directive for messages, e.g. `Material "conductor" at scene.pbrt:5:1` (empty
    // for a material made in code).
    std::string label;

protected:
    std::unique_ptr<const BxDF> constant_;
    std::shared_ptr<const ShadingDetail> detail_;
    bool needsDerivatives_ = false;
};

}  // namespace ps
