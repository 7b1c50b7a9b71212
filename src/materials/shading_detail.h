// Bump mapping ("displacement") and normal mapping ("normalmap") with pbrt-v4's semantics
// (PBRT-CONVENTIONS "Normal and bump maps"): a map replaces the shading frame of a hit before
// its BSDF is built, and every integrator then uses that one frame (integrator.h surfaceBxDF).
//
// No ray differentials: this renderer traces no ray differentials and estimates no uv
// footprint, so du = dv = 0.0005, the step pbrt-v4 takes when its uv derivatives are zero
// (as with its --disabletexturefiltering); pbrt-v4 otherwise steps half the pixel footprint.
#pragma once
#include <memory>
#include "geometry/interaction.h"
#include "materials/image_texture.h"
#include "materials/texture.h"

namespace ps {

class ShadingDetail {
public:
    // The finite-difference step in u and v for bump mapping.
    static constexpr float kBumpDelta = 0.0005f;

    // A normal map: tangent-space normals as 2c - 1 of an RGB image (read linearly, so 8-bit
    // formats other than PNG arrive sRGB-decoded, as in pbrt-v4).
    static std::shared_ptr<const ShadingDetail> normalMap(std::shared_ptr<const Image> image);
    // A bump map: the float texture displaces the surface along its shading normal.
    static std::shared_ptr<const ShadingDetail> bumpMap(std::shared_ptr<FloatTexture> displacement);

    // Replaces si.ns, si.dpdu and si.dpdv (which the hit's shape filled, with dndu and dndv)
    // by the mapped frame, its normal on the side of si.ng. Leaves si unchanged where the
    // mapped frame is degenerate (zero or non-finite), so a map never produces a NaN.
    void apply(SurfaceInteraction& si) const;

private:
    void normalMapped(const SurfaceInteraction& si, Vec3& dpdu, Vec3& dpdv) const;
    void bumped(const SurfaceInteraction& si, Vec3& dpdu, Vec3& dpdv) const;

    std::unique_ptr<ImageLookup> lookup_;  // the normal map (repeat wrap, bilinear), or null
    std::shared_ptr<FloatTexture> displacement_;
};

}  // namespace ps
