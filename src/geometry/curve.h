// pbrt-v4's "curve" shape on Embree's native curve primitives: every segment becomes one cubic
// Bezier segment; "flat" curves are Embree's flat (ray-facing) curves, "ribbon" curves its
// normal-oriented curves and "cylinder" curves its round (swept-circle) curves.
#pragma once
#include <array>
#include <string>
#include <vector>
#include "geometry/shape.h"
#include "math/transform.h"

namespace ps {

enum class CurveType { Flat, Ribbon, Cylinder };

// A curve as the scene file gives it (object space), validated and converted by makeSegments.
struct CurveInput {
    std::vector<Vec3> P;
    std::vector<Vec3> N;  // ribbon: one normal per segment end (segments + 1)
    int degree = 3;       // 2 or 3
    bool bspline = false; // uniform B-spline basis, else Bezier
    CurveType type = CurveType::Flat;
    float width0 = 1, width1 = 1;
};

// Cubic Bezier segments with pbrt-v4's per-segment widths and end normals, object space.
struct CurveSegments {
    std::vector<std::array<Vec3, 4>> cp;
    std::vector<std::array<float, 2>> width;  // at u = 0 and u = 1 of each segment
    std::vector<std::array<Vec3, 2>> n;       // ribbon only
};

// The segments of `in` following pbrt-v4: Bezier curves share end points (degree + 1 points,
// then degree more per segment), B-splines have points - degree segments; degree 2 is raised
// to 3 exactly; the width goes linearly from width0 to width1 over the segments. Returns an
// error message (empty on success).
std::string makeSegments(const CurveInput& in, CurveSegments& out);

// Exact conversions to cubic Bezier control points.
std::array<Vec3, 4> elevateQuadraticBezier(const Vec3* q);
std::array<Vec3, 4> quadraticBSplineToBezier(const Vec3* p);
std::array<Vec3, 4> cubicBSplineToBezier(const Vec3* p);

class Curve final : public Shape {
public:
    // Control points go to scene space; widths scale with the transform's mean scale factor.
    Curve(const CurveSegments& segments, CurveType type, const Transform& toScene, bool reverseOrientation);

    RTCGeometry buildGeometry(RTCDevice device) const override;
    int primitiveCount() const override { return int(index_.size()); }
    int interaction(const Ray& r, float t, int embreePrim, float u, float v, SurfaceInteraction& si) const override;
    // pbrt-v4's estimate: control polygon length times mean width (curves cannot emit).
    float area(int prim) const override;
    // Never called: area lights on curves are rejected when the scene is built.
    ShapeSample sampleArea(int prim, Vec2 u) const override;
    // The control points' box widened by the segment's largest radius (Bezier hull).
    Bounds3 primitiveBounds(int prim) const override;

    // Embree's filters reject cut-outs and, on flat curves, hits on the curve the ray starts on.
    bool acceptsHit(const Ray& r, float t, int embreePrim, float u, float v) const override;
    CurveType type() const { return type_; }

private:
    // Centre point, derivative and radius of segment seg at u.
    Vec3 centre(int seg, float u, Vec3* dcdu, float* radius) const;
    Vec3 ribbonNormal(int seg, float u) const;  // pbrt-v4's spherical interpolation of the end normals
    int tessellationRate() const;
    // Whether a ray from o starts on flat segment seg that Embree reports hit at u (curve.cpp).
    bool isSelfHit(Vec3 o, int seg, float u) const;

    CurveType type_;
    bool flip_;                   // ReverseOrientation XOR the transform swaps handedness
    std::vector<float> cp_;       // x y z radius per control point, 4 per segment (Embree's buffer)
    std::vector<float> cpNormal_; // ribbon: x y z per control point, Bezier normals for Embree
    std::vector<Vec3> endNormal_; // ribbon: unit end normals, 2 per segment
    std::vector<unsigned> index_; // first control point of each segment
};

}  // namespace ps
