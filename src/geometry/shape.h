// A shape is one Embree geometry made of primitives (triangles, or a single quadric).
// Area lights sample shapes by primitive; integrators only see SurfaceInteraction.
#pragma once
#include <embree3/rtcore.h>
#include <memory>
#include <optional>
#include <vector>
#include "geometry/alpha_mask.h"
#include "geometry/interaction.h"
#include "geometry/ray.h"
#include "math/bounds3.h"
#include "math/direction_cone.h"

namespace ps {

class Medium;

struct ShapeSample {
    Vec3 p, n;          // point and its oriented geometric normal
    Vec2 uv;
    float pdf = 0;      // area measure for sampleArea, solid angle for sampleToward
    Vec3 wi;            // sampleToward only: unit direction from the reference point
    float pdfArea = 0;  // sampleToward only: the area density sampleArea has at p (what a
                        // light subpath starting on the shape needs for its weights)
};

class Shape {
public:
    virtual ~Shape() = default;
    // Creates the committed Embree geometry (not attached to a scene).
    virtual RTCGeometry buildGeometry(RTCDevice device) const = 0;
    virtual int primitiveCount() const = 0;
    // Fills geometry fields of si (p, ng, ns, dpdu, uv) for Embree's hit of its primitive
    // embreePrim at its (u, v) by ray r at distance t, and returns the shape's own primitive
    // index (the numbering of areaLights and sampling; Embree's may differ, e.g. for quads).
    // When material->needsShadingDerivatives(), it also fills dpdv, dndu, dndv and sets dpdu
    // to pbrt-v4's shading dp/du (a shape that does not leaves bump and normal maps inert).
    virtual int interaction(const Ray& r, float t, int embreePrim, float u, float v, SurfaceInteraction& si) const = 0;
    virtual float area(int prim) const = 0;
    // Uniform by area over the primitive.
    virtual ShapeSample sampleArea(int prim, Vec2 u) const = 0;
    // The area density sampleArea uses on the primitive.
    virtual float pdfArea(int prim) const {
        float a = area(prim);
        return a > 0 ? 1 / a : 0.0f;
    }
    // Sample a point as seen from ref; pdf in solid angle at ref. Default: area sampling.
    virtual std::optional<ShapeSample> sampleToward(int prim, Vec3 ref, Vec2 u) const;
    // Solid-angle pdf at ref of sampleToward producing the point hit (dist2 = |hit - ref|^2).
    virtual float pdfToward(int prim, Vec3 ref, Vec3 hitP, Vec3 hitN) const;
    // Called once for emissive shapes: cache what light sampling needs per primitive.
    virtual void prepareSampling() {}
    // What choosing lights by their bounds needs of an emitting primitive (lights/light_bounds.h):
    // a box holding it, in the space the shape is stored in, and a cone holding its oriented
    // normals (the side a one-sided emitter emits from). Default: normals in every direction.
    virtual Bounds3 primitiveBounds(int prim) const = 0;
    virtual DirectionCone normalBounds(int prim) const {
        (void)prim;
        return DirectionCone::entireSphere();
    }

    // The alpha test of Embree's hit (embreePrim, u, v) at distance t of ray r, r in the space
    // the shape is stored in (the world's, or an instance prototype's): true without alpha.
    // Emitters test the point, not the ray, so that a point is either present or cut out for
    // rays and for emission alike (see DiffuseAreaLight::L).
    bool keepsHit(const Ray& r, float t, int embreePrim, float u, float v) const;

    const Material* material = nullptr;
    // Its MediumInterface when a transition (inside != outside): a ray crossing it changes
    // medium (both null otherwise: the ray keeps its own, as pbrt-v4's primitives do).
    const Medium* mediumInside = nullptr;
    const Medium* mediumOutside = nullptr;
    bool mediumTransition = false;
    std::shared_ptr<const AlphaMask> alpha;  // null: opaque (no filter, no cost)
    // Per-primitive emitters (empty when the shape does not emit).
    std::vector<const Light*> areaLights;
    // An emitter whose radiance varies over uv (an emission image): sampled points need uv.
    bool emissionNeedsUV = false;

protected:
    // For Embree's own primitives (triangles, quads, curves): with alpha, installs intersection
    // and occlusion filters that apply acceptsHit, so closest hits and shadow rays (also inside
    // instances) skip cut-out hits. Without alpha it installs nothing.
    void installAlphaFilter(RTCGeometry g) const;
    // Installs those filters unconditionally (a shape that rejects hits for other reasons).
    void installHitFilter(RTCGeometry g) const;

public:
    // What the filters ask of each candidate hit: by default the alpha test.
    virtual bool acceptsHit(const Ray& r, float t, int embreePrim, float u, float v) const {
        return keepsHit(r, t, embreePrim, u, v);
    }
};

}  // namespace ps
