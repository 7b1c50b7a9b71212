// What an integrator knows about a ray's hit point.
#pragma once
#include "geometry/fibre_kind.h"
#include "math/frame.h"
#include "math/vec.h"

namespace ps {

class Material;
class Light;
class Medium;

struct SurfaceInteraction {
    Vec3 p;
    float t = 0;
    Vec3 ng;        // geometric normal, oriented by pbrt's rules (winding/N/ReverseOrientation)
    Vec3 ns;        // shading normal, in the hemisphere of ng
    Vec3 dpdu;      // shading tangent along u
    // pbrt-v4's shading dp/dv and dn/du, dn/dv: filled (and dpdu set to pbrt-v4's shading
    // dp/du) only where the material has a bump or normal map, which reads them
    // (Material::needsShadingDerivatives); zero elsewhere.
    Vec3 dpdv, dndu, dndv;
    Vec2 uv;
    Vec3 wo;        // towards the ray origin
    const Material* material = nullptr;
    const Light* areaLight = nullptr;  // the emitter at this point, if any
    // The shape's media when it bounds a medium (mediumTransition); a ray leaving here on
    // the side of ng enters the outside one (pbrt-v4's SpawnRay).
    const Medium* mediumInside = nullptr;
    const Medium* mediumOutside = nullptr;
    bool mediumTransition = false;
    const Medium* mediumToward(Vec3 w, const Medium* current) const {
        return mediumTransition ? (dot(w, ng) > 0 ? mediumOutside : mediumInside) : current;
    }

    // dpdu is already the unit tangent of the shading frame (orthogonal to ns), as triangles
    // with a fixed normal precompute it, so the frame needs no Gram-Schmidt step per hit.
    bool tangentIsFrameAxis = false;
    FibreKind fibre = FibreKind::None;  // curves only (geometry/fibre_kind.h)

    Frame shadingFrame() const {
        return tangentIsFrameAxis ? Frame(dpdu, cross(ns, dpdu), ns) : Frame::fromNormalTangent(ns, dpdu);
    }
};

}  // namespace ps
