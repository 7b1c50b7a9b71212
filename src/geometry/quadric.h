// Spheres, disks and cylinders as exact implicit surfaces, intersected in object space through
// Embree's user-geometry callbacks.
#pragma once
#include "geometry/shape.h"
#include "math/transform.h"

namespace ps {

class Quadric : public Shape {
public:
    Quadric(const Transform& toScene, bool reverseOrientation)
        : toScene_(toScene), flip_(reverseOrientation ^ toScene.swapsHandedness()) {}
    RTCGeometry buildGeometry(RTCDevice device) const override;
    int primitiveCount() const override { return 1; }
    // Object-space ray-surface test: nearest t in (tMin, tMax), or a negative value (a larger
    // tMin finds the hits behind one that alpha cut out).
    virtual float intersectObject(Vec3 o, Vec3 d, float tMin, float tMax) const = 0;
    virtual void objectBounds(Vec3& lo, Vec3& hi) const = 0;
    // The object bounds' eight corners carried to the shape's space.
    Bounds3 primitiveBounds(int prim) const override;
    const Transform& toScene() const { return toScene_; }
    // The nearest hit in (0, tMax) that the alpha test keeps, or a negative value; o, d are
    // the ray in the shape's space (sceneRay) and in object space.
    float nearestKeptHit(const Ray& sceneRay, Vec3 o, Vec3 d, float tMax) const;

protected:
    // Whether hits must carry pbrt-v4's shading derivatives (a bump or normal map).
    bool wantsDerivatives() const;
    // Stores object-space dp/du, dp/dv, dn/du, dn/dv in si, in scene space.
    void setDerivatives(SurfaceInteraction& si, Vec3 dpdu, Vec3 dpdv, Vec3 dndu, Vec3 dndv) const;

    Transform toScene_;
    bool flip_;
};

class Sphere final : public Quadric {
public:
    Sphere(const Transform& toScene, bool reverseOrientation, float radius, float zMin, float zMax, float phiMaxDeg);
    float intersectObject(Vec3 o, Vec3 d, float tMin, float tMax) const override;
    void objectBounds(Vec3& lo, Vec3& hi) const override;
    int interaction(const Ray& r, float t, int embreePrim, float u, float v, SurfaceInteraction& si) const override;
    float area(int prim) const override;
    ShapeSample sampleArea(int prim, Vec2 u) const override;
    // Partial spheres sample the full sphere and reject points outside the part.
    float pdfArea(int) const override { return 1.0f / (4 * kPi * sceneRadius_ * sceneRadius_); }
    std::optional<ShapeSample> sampleToward(int prim, Vec3 ref, Vec2 u) const override;
    float pdfToward(int prim, Vec3 ref, Vec3 hitP, Vec3 hitN) const override;

private:
    bool inRange(Vec3 pObj) const;
    bool isFull() const { return full_; }
    float radius_, zMin_, zMax_, thetaZMin_, thetaZMax_, phiMax_;
    bool full_;
    Vec3 center_;        // scene-space centre
    float sceneRadius_;  // radius in scene space (uniform scale assumed for sampling)
};

class Disk final : public Quadric {
public:
    Disk(const Transform& toScene, bool reverseOrientation, float height, float radius, float innerRadius, float phiMaxDeg);
    float intersectObject(Vec3 o, Vec3 d, float tMin, float tMax) const override;
    void objectBounds(Vec3& lo, Vec3& hi) const override;
    int interaction(const Ray& r, float t, int embreePrim, float u, float v, SurfaceInteraction& si) const override;
    float area(int prim) const override;
    ShapeSample sampleArea(int prim, Vec2 u) const override;
    DirectionCone normalBounds(int prim) const override;  // flat: its one oriented normal

private:
    float height_, radius_, innerRadius_, phiMax_;
};

// pbrt-v4's "cylinder": x^2 + y^2 = r^2 for zMin <= z <= zMax and phi <= phiMax, no caps;
// the normal points away from the axis; u = phi / phiMax, v = (z - zMin) / (zMax - zMin).
class Cylinder final : public Quadric {
public:
    Cylinder(const Transform& toScene, bool reverseOrientation, float radius, float zMin, float zMax, float phiMaxDeg);
    float intersectObject(Vec3 o, Vec3 d, float tMin, float tMax) const override;
    void objectBounds(Vec3& lo, Vec3& hi) const override;
    int interaction(const Ray& r, float t, int embreePrim, float u, float v, SurfaceInteraction& si) const override;
    float area(int prim) const override;
    // Uniform in (phi, z): uniform in area when the transform scales x and y alike.
    ShapeSample sampleArea(int prim, Vec2 u) const override;

private:
    Vec3 normalAt(Vec3 pObj) const;
    float radius_, zMin_, zMax_, phiMax_;
};

}  // namespace ps
