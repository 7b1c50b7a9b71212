#include "geometry/curve.h"

#include <algorithm>
#include <cmath>

#include "materials/material.h"

namespace ps {

namespace {

// Cubic Bernstein weights at u and their derivatives.
void bernstein(float u, float b[4], float db[4]) {
    float s = 1 - u;
    b[0] = s * s * s;
    b[1] = 3 * s * s * u;
    b[2] = 3 * s * u * u;
    b[3] = u * u * u;
    db[0] = -3 * s * s;
    db[1] = 3 * s * (s - 2 * u);
    db[2] = 3 * u * (2 * s - u);
    db[3] = 3 * u * u;
}

// v / |v|, or `fallback` where v is zero or not finite.
Vec3 normalizeOr(Vec3 v, Vec3 fallback) {
    float l2 = lengthSquared(v);
    return l2 > 0 && std::isfinite(l2) ? v / std::sqrt(l2) : fallback;
}

// Some unit vector perpendicular to the unit vector a.
Vec3 anyPerpendicular(Vec3 a) {
    Vec3 s, t;
    coordinateSystem(a, s, t);
    return s;
}

// The mean length scale of the transform's linear part (exact for similarity transforms):
// pbrt-v4 measures widths in object space.
float meanScale(const Transform& T) {
    const auto& m = T.matrix().m;
    float det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    return std::cbrt(std::fabs(det));
}

}  // namespace

std::array<Vec3, 4> elevateQuadraticBezier(const Vec3* q) {
    return {q[0], q[0] / 3.0f + q[1] * (2.0f / 3.0f), q[1] * (2.0f / 3.0f) + q[2] / 3.0f, q[2]};
}

std::array<Vec3, 4> quadraticBSplineToBezier(const Vec3* p) {
    const Vec3 q[3] = {(p[0] + p[1]) * 0.5f, p[1], (p[1] + p[2]) * 0.5f};
    return elevateQuadraticBezier(q);
}

std::array<Vec3, 4> cubicBSplineToBezier(const Vec3* p) {
    return {(p[0] + p[1] * 4.0f + p[2]) / 6.0f, (p[1] * 2.0f + p[2]) / 3.0f, (p[1] + p[2] * 2.0f) / 3.0f,
            (p[1] + p[2] * 4.0f + p[3]) / 6.0f};
}

std::string makeSegments(const CurveInput& in, CurveSegments& out) {
    const int degree = in.degree;
    if (degree != 2 && degree != 3)
        return "invalid \"degree\" " + std::to_string(degree) + ": only degree 2 and 3 curves are supported";
    const size_t nP = in.P.size();
    size_t nSeg = 0;
    if (!in.bspline) {
        if (nP < size_t(degree) + 1 || (nP - 1 - degree) % degree != 0)
            return "invalid number of control points " + std::to_string(nP) + ": the degree " + std::to_string(degree) +
                   " Bezier basis needs " + std::to_string(degree + 1) + " + n * " + std::to_string(degree) + " (n >= 0)";
        nSeg = (nP - 1) / degree;
    } else {
        if (nP < size_t(degree) + 1)
            return "invalid number of control points " + std::to_string(nP) + ": the degree " + std::to_string(degree) +
                   " b-spline basis needs at least " + std::to_string(degree + 1);
        nSeg = nP - degree;
    }
    if (in.type == CurveType::Ribbon) {
        if (in.N.empty()) return "ribbon curves need normals \"N\" at the segment ends";
        if (in.N.size() != nSeg + 1)
            return "invalid number of normals " + std::to_string(in.N.size()) + ": ribbon curves with " +
                   std::to_string(nSeg) + " segments need " + std::to_string(nSeg + 1);
        for (Vec3 n : in.N)
            if (!(lengthSquared(n) > 0)) return "the normals \"N\" must not be zero";
    }
    out = {};
    for (size_t s = 0; s < nSeg; ++s) {
        // Bezier segments share their end point; B-spline segments slide by one point.
        const Vec3* p = &in.P[in.bspline ? s : s * degree];
        if (in.bspline)
            out.cp.push_back(degree == 2 ? quadraticBSplineToBezier(p) : cubicBSplineToBezier(p));
        else
            out.cp.push_back(degree == 2 ? elevateQuadraticBezier(p) : std::array<Vec3, 4>{p[0], p[1], p[2], p[3]});
        out.width.push_back({lerp(float(s) / nSeg, in.width0, in.width1), lerp(float(s + 1) / nSeg, in.width0, in.width1)});
        if (in.type == CurveType::Ribbon) out.n.push_back({normalize(in.N[s]), normalize(in.N[s + 1])});
    }
    return {};
}

Curve::Curve(const CurveSegments& segs, CurveType type, const Transform& toScene, bool reverseOrientation)
    : type_(type), flip_(reverseOrientation ^ toScene.swapsHandedness()) {
    const float scale = meanScale(toScene);
    const size_t nSeg = segs.cp.size();
    cp_.reserve(nSeg * 16);
    for (size_t s = 0; s < nSeg; ++s) {
        index_.push_back(unsigned(4 * s));
        for (int i = 0; i < 4; ++i) {
            Vec3 p = toScene.point(segs.cp[s][i]);
            // Bezier control values at i/3 of a linear function reproduce it exactly.
            float radius = 0.5f * scale * lerp(i / 3.0f, segs.width[s][0], segs.width[s][1]);
            cp_.insert(cp_.end(), {p.x, p.y, p.z, radius});
        }
    }
    // Embree reads its buffers with 16-byte loads: pad the index buffer past its last element.
    index_.reserve(index_.size() + 3);
    if (type_ != CurveType::Ribbon) return;
    for (size_t s = 0; s < nSeg; ++s) {
        Vec3 n0 = normalizeOr(toScene.normal(segs.n[s][0]), {0, 0, 1});
        Vec3 n1 = normalizeOr(toScene.normal(segs.n[s][1]), n0);
        endNormal_.push_back(n0);
        endNormal_.push_back(n1);
        // Embree interpolates normals as a Bezier curve and uses only their direction: the
        // standard cubic arc through n0 and n1 (end tangents of length 4/3 tan(theta/4))
        // follows the great circle pbrt-v4 interpolates along, to within 3e-4 of its radius
        // up to 90 degrees.
        float theta = safeAcos(dot(n0, n1));
        Vec3 c1 = n0, c2 = n1;
        if (theta > 1e-4f) {
            Vec3 t0 = normalizeOr(n1 - n0 * dot(n0, n1), anyPerpendicular(n0));
            Vec3 t1 = normalizeOr(n1 * dot(n0, n1) - n0, -anyPerpendicular(n0));
            float k = 4.0f / 3.0f * std::tan(theta / 4);
            c1 = n0 + t0 * k;
            c2 = n1 - t1 * k;
        }
        for (Vec3 c : {n0, c1, c2, n1}) cpNormal_.insert(cpNormal_.end(), {c.x, c.y, c.z});
    }
    cpNormal_.push_back(0);  // padding for 16-byte loads
}

Vec3 Curve::centre(int seg, float u, Vec3* dcdu, float* radius) const {
    float b[4], db[4];
    bernstein(u, b, db);
    const float* c = &cp_[16 * size_t(seg)];
    Vec3 p, d;
    float r = 0;
    for (int i = 0; i < 4; ++i) {
        Vec3 q(c[4 * i], c[4 * i + 1], c[4 * i + 2]);
        p = p + q * b[i];
        d = d + q * db[i];
        r += c[4 * i + 3] * b[i];
    }
    if (dcdu) *dcdu = d;
    if (radius) *radius = r;
    return p;
}

Vec3 Curve::ribbonNormal(int seg, float u) const {
    Vec3 n0 = endNormal_[2 * size_t(seg)], n1 = endNormal_[2 * size_t(seg) + 1];
    float theta = safeAcos(dot(n0, n1));
    if (theta < 1e-4f) return n0;
    float inv = 1 / std::sin(theta);
    return normalizeOr(n0 * (std::sin((1 - u) * theta) * inv) + n1 * (std::sin(u * theta) * inv), n0);
}

// Flat curves are ray-facing quads, `rate` per segment. A cubic with second differences of
// at most L0 strays from its chords by at most 6 L0 / (8 rate^2); keeping that below a 20th
// of the width (the tolerance pbrt-v4 subdivides its curves to) needs rate^2 >= 15 L0 / w.
int Curve::tessellationRate() const {
    float worst = 0;
    for (size_t s = 0; s < index_.size(); ++s) {
        const float* c = &cp_[16 * s];
        float l0 = 0, w = 0;
        for (int i = 0; i < 2; ++i) {
            Vec3 a(c[4 * i], c[4 * i + 1], c[4 * i + 2]), b(c[4 * i + 4], c[4 * i + 5], c[4 * i + 6]),
                d(c[4 * i + 8], c[4 * i + 9], c[4 * i + 10]);
            l0 = std::max(l0, length(a - b * 2.0f + d));
        }
        for (int i = 0; i < 4; ++i) w = std::max(w, 2 * c[4 * i + 3]);
        if (w > 0) worst = std::max(worst, 15 * l0 / w);
    }
    return int(clampf(std::ceil(std::sqrt(worst)), 1, 64));
}

RTCGeometry Curve::buildGeometry(RTCDevice device) const {
    // Cylinder curves are flat ones shaded as tubes (interaction), as in pbrt-v4.
    RTCGeometryType kind = type_ == CurveType::Ribbon ? RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE
                                                      : RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE;
    RTCGeometry g = rtcNewGeometry(device, kind);
    const size_t nVertices = cp_.size() / 4;
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, cp_.data(), 0, 4 * sizeof(float), nVertices);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, index_.data(), 0, sizeof(unsigned),
                               index_.size());
    if (type_ == CurveType::Ribbon)
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, cpNormal_.data(), 0,
                                   3 * sizeof(float), nVertices);
    if (type_ != CurveType::Ribbon) rtcSetGeometryTessellationRate(g, float(tessellationRate()));
    if (type_ != CurveType::Ribbon)
        installHitFilter(g);  // self hits, see isSelfHit
    else
        installAlphaFilter(g);
    rtcCommitGeometry(g);
    return g;
}

// A ray leaving a flat curve must not find it again where it starts: the curve turns to face
// every ray, so a ray starting on it (spawned a hair's breadth off it) can pass within the
// radius of the centre line near its own origin, or further along when it leaves at a grazing
// angle (measured: 0.5% of the rays leaving a straight flat curve without this test; ribbons,
// real strips, are not found again). So a flat segment's hits are rejected when the ray
// starts within the radius of its centre line; like a tube, a flat curve that curls back
// within one segment does not shadow itself. Cylinder curves are such ray-facing strips too,
// shaded as tubes: a ray leaving one into the tube (a hair BSDF's transmission through the
// fibre) passes.
bool Curve::isSelfHit(Vec3 o, int seg, float u) const {
    const float* q = &cp_[16 * size_t(seg)];
    const float tolAbs = 4e-5f * (1 + std::max({std::fabs(o.x), std::fabs(o.y), std::fabs(o.z)}));
    float reach = std::max(std::max(q[3], q[7]), std::max(q[11], q[15])) * 1.01f + tolAbs;
    for (int i = 0; i < 3; ++i)
        reach += length(Vec3(q[4 * i + 4] - q[4 * i], q[4 * i + 5] - q[4 * i + 1], q[4 * i + 6] - q[4 * i + 2]));
    Vec3 dcdu;
    float r;
    Vec3 c = centre(seg, u, &dcdu, &r);
    if (lengthSquared(o - c) > reach * reach) return false;  // the origin is nowhere near this segment
    // The centre point nearest the origin: Gauss-Newton steps from the hit's u.
    float uo = u;
    for (int i = 0; i < 4; ++i) {
        float h = lengthSquared(dcdu);
        if (!(h > 0)) break;
        uo = clampf(uo - dot(c - o, dcdu) / h, 0, 1);
        c = centre(seg, uo, &dcdu, &r);
    }
    return length(o - c) <= r * 1.01f + tolAbs;
}

bool Curve::acceptsHit(const Ray& r, float t, int embreePrim, float u, float v) const {
    return !(type_ != CurveType::Ribbon && isSelfHit(r.o, embreePrim, u)) && keepsHit(r, t, embreePrim, u, v);
}

// pbrt-v4's hit data: u along the segment; v across it from 0 to 1, increasing towards
// d x dp/du (for ribbons, the distance from the centre over the width); dp/du the curve's
// derivative; dp/dv across the curve with length the width, and the normal
// dp/du x dp/dv flipped by ReverseOrientation XOR a handedness swap. That normal faces away
// from the ray on flat and cylinder curves and is the end normals' interpolation made
// perpendicular to the curve on ribbons.
//
// Cylinder curves are pbrt-v4's: the flat curve's strip facing the ray, its geometric normal
// the strip's, its shading normal turned about the curve by theta = (v - 1/2) pi, so that
// across the strip it sweeps as a tube's does (at the edges perpendicular to the ray). The
// strip faces every ray, so the fibre is met over its projected width by every technique
// (FibreKind::FacingRay): a true tube, whose far side a light path could find and connect to
// the camera through the tube itself, would give light tracing and BDPT a fibre that the
// camera's rays never see (+0.4% and +0.55% on the matrix's hair cell). The shading normal
// is tilted towards the side of the hit, as on a tube seen from the ray's origin (it faces
// away from the ray, as the strip's normal does; theta linear in v, as pbrt-v4's).
int Curve::interaction(const Ray& r, float t, int embreePrim, float u, float v, SurfaceInteraction& si) const {
    (void)v;
    const int seg = embreePrim;
    Vec3 dcdu;
    float radius;
    Vec3 c = centre(seg, u, &dcdu, &radius);
    Vec3 p = r.o + r.d * t;
    Vec3 d = normalizeOr(r.d, {0, 0, 1});
    const float* q = &cp_[16 * size_t(seg)];
    Vec3 tangent = normalizeOr(dcdu, normalizeOr(Vec3(q[12] - q[0], q[13] - q[1], q[14] - q[2]), anyPerpendicular(d)));
    Vec3 across = normalizeOr(cross(d, tangent), anyPerpendicular(tangent));
    const float width = 2 * radius;
    const float invWidth = width > 0 ? 1 / width : 0.0f;
    Vec3 off = p - c;
    Vec3 n = cross(tangent, across);  // flat: d made perpendicular to the curve, unit
    Vec3 dpdv = across * width;
    float vHit = 0.5f + dot(off, across) * invWidth;
    if (type_ == CurveType::Ribbon) {
        Vec3 nr = ribbonNormal(seg, u);
        n = normalizeOr(nr - tangent * dot(nr, tangent), n);
        dpdv = normalizeOr(cross(nr, tangent), across) * (width * std::fabs(dot(nr, d)));
        vHit = 0.5f + std::copysign(length(off), dot(off, across)) * invWidth;
    }
    Vec3 ns = n;
    if (type_ == CurveType::Cylinder) {
        const float theta = (clampf(vHit, 0, 1) - 0.5f) * kPi;
        ns = n * std::cos(theta) - across * std::sin(theta);
        dpdv = normalizeOr(cross(ns, tangent), across) * width;
    }
    if (flip_) {
        n = -n;
        ns = -ns;
    }
    si.p = p;
    si.t = t;
    si.ng = n;
    si.ns = ns;
    si.dpdu = dcdu;
    si.tangentIsFrameAxis = false;
    si.fibre = type_ == CurveType::Ribbon ? FibreKind::None : FibreKind::FacingRay;
    si.uv = Vec2(u, clampf(vHit, 0, 1));
    if (material && material->needsShadingDerivatives()) {
        si.dpdv = dpdv;
        si.dndu = Vec3();
        si.dndv = Vec3();
    }
    return seg;
}

float Curve::area(int prim) const {
    const float* c = &cp_[16 * size_t(prim)];
    float len = 0;
    for (int i = 0; i < 3; ++i)
        len += length(Vec3(c[4 * i + 4] - c[4 * i], c[4 * i + 5] - c[4 * i + 1], c[4 * i + 6] - c[4 * i + 2]));
    return len * (c[3] + c[15]);  // mean width = sum of the end radii
}

ShapeSample Curve::sampleArea(int, Vec2) const { return ShapeSample{}; }

Bounds3 Curve::primitiveBounds(int prim) const {
    const float* c = &cp_[16 * size_t(prim)];
    Bounds3 b;
    float r = 0;
    for (int i = 0; i < 4; ++i) {
        b.expand(Vec3(c[4 * i], c[4 * i + 1], c[4 * i + 2]));
        r = std::max(r, c[4 * i + 3]);
    }
    b.lo -= Vec3(r, r, r);
    b.hi += Vec3(r, r, r);
    return b;
}

}  // namespace ps
