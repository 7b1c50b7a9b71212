// Triangle meshes (trianglemesh, plymesh, triangulated bilinear patches), stored in the
// space of the scene that holds them (world, or an instance prototype's space).
#pragma once
#include <vector>
#include "geometry/quad_pairing.h"
#include "geometry/shape.h"
#include "math/transform.h"

namespace ps {

struct TriangleMeshData {
    std::vector<Vec3> P;       // object space
    std::vector<Vec3> N;       // optional, object space
    std::vector<Vec2> uv;      // optional
    std::vector<int> indices;  // 3 per triangle
};

class TriangleMesh final : public Shape {
public:
    // Transforms the data by `toScene`; orientation follows PBRT-CONVENTIONS §4: the
    // winding normal carried through the transform, flipped by ReverseOrientation; with N,
    // the shading normal decides and the geometric normal follows it.
    TriangleMesh(TriangleMeshData data, const Transform& toScene, bool reverseOrientation);

    RTCGeometry buildGeometry(RTCDevice device) const override;
    int primitiveCount() const override { return int(indices_.size() / 3); }
    int interaction(const Ray& r, float t, int embreePrim, float u, float v, SurfaceInteraction& si) const override;
    float area(int prim) const override;
    ShapeSample sampleArea(int prim, Vec2 u) const override;
    std::optional<ShapeSample> sampleToward(int prim, Vec3 ref, Vec2 u) const override;
    void prepareSampling() override;
    Bounds3 primitiveBounds(int prim) const override;
    // The emitting side's normal: the one light sampling gives (the side N chooses), or every
    // direction where N disagrees with itself over the triangle.
    DirectionCone normalBounds(int prim) const override;

private:
    Vec3 geometricNormal(int prim) const { return faceNormal_[prim]; }  // unit, oriented
    Vec2 uvAt(int vertex, int corner) const;
    // pbrt-v4's shading dp/du, dp/dv, dn/du, dn/dv (constant over a triangle), for bump and
    // normal maps; si.ns must already hold the shading normal.
    void shadingDerivatives(int prim, SurfaceInteraction& si) const;

    std::vector<float> positions_;  // xyz per vertex plus padding for Embree's SSE loads
    std::vector<Vec3> normals_;
    std::vector<Vec2> uv_;
    std::vector<unsigned> indices_;
    QuadPairing quads_;  // what Embree traces when most triangles pair up (else empty)
    // Per triangle: oriented unit geometric normal and dp/du, computed once (24 bytes per
    // triangle) instead of at every hit.
    std::vector<Vec3> faceNormal_, faceDpdu_;
    // Per triangle, with N: its three normals are equal, so the shading normal is that one
    // normal everywhere on it (flat-shaded exports) and needs no interpolation.
    std::vector<uint8_t> flatNormals_;
    // Per triangle whose shading normal is fixed (no N, or flat N): faceDpdu_ holds the
    // shading frame's unit tangent, Gram-Schmidt done once here instead of at every hit.
    std::vector<uint8_t> tangentIsFrameAxis_;
    bool flipNormal_ = false;  // ReverseOrientation XOR transform swaps handedness
    // Per triangle, filled by prepareSampling for emitters: vertex 0, edges, oriented
    // geometric normal and area, so light sampling touches one cache line per triangle.
    struct SamplingData {
        Vec3 p0, e1, e2, n;
        float area;
        bool normalsMayFlip;  // interpolated N disagrees with n somewhere on the triangle
    };
    std::vector<SamplingData> sampling_;
};

}  // namespace ps
