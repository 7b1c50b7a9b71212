#include "geometry/triangle_mesh.h"

#include "materials/material.h"
#include "math/warp.h"

namespace ps {

static inline Vec3 loadP(const std::vector<float>& p, unsigned i) { return {p[3 * i], p[3 * i + 1], p[3 * i + 2]}; }

TriangleMesh::TriangleMesh(TriangleMeshData data, const Transform& toScene, bool reverseOrientation) {
    positions_.resize(data.P.size() * 3 + 1);  // +1 float: Embree reads 16 bytes per vertex
    for (size_t i = 0; i < data.P.size(); ++i) {
        Vec3 p = toScene.point(data.P[i]);
        positions_[3 * i] = p.x;
        positions_[3 * i + 1] = p.y;
        positions_[3 * i + 2] = p.z;
    }
    if (data.N.size() == data.P.size()) {
        normals_.resize(data.N.size());
        for (size_t i = 0; i < data.N.size(); ++i) {
            Vec3 n = toScene.normal(data.N[i]);
            float l = length(n);
            normals_[i] = l > 0 ? n / l : Vec3(0, 0, 0);
            if (reverseOrientation) normals_[i] = -normals_[i];
        }
    }
    if (data.uv.size() == data.P.size()) uv_ = std::move(data.uv);
    indices_.assign(data.indices.begin(), data.indices.end());
    flipNormal_ = reverseOrientation ^ toScene.swapsHandedness();
    quads_ = pairTriangles(indices_);
    int n = primitiveCount();
    faceNormal_.resize(n);
    faceDpdu_.resize(n);
    for (int i = 0; i < n; ++i) {
        const unsigned* vi = &indices_[3 * i];
        Vec3 p0 = loadP(positions_, vi[0]), p1 = loadP(positions_, vi[1]), p2 = loadP(positions_, vi[2]);
        Vec3 ng = cross(p1 - p0, p2 - p0);
        float l = length(ng);
        ng = l > 0 ? ng / l : Vec3(0, 0, 1);
        faceNormal_[i] = flipNormal_ ? -ng : ng;
        // dp/du from the uv parameterisation. Degenerate or non-finite tangents are replaced
        // by Frame::fromNormalTangent, which falls back to an arbitrary tangent.
        Vec2 uv0 = uvAt(vi[0], 0), uv1 = uvAt(vi[1], 1), uv2 = uvAt(vi[2], 2);
        Vec2 duv02 = uv0 - uv2, duv12 = uv1 - uv2;
        float det = duv02.x * duv12.y - duv02.y * duv12.x;
        faceDpdu_[i] = det != 0 ? ((p0 - p2) * duv12.y - (p1 - p2) * duv02.y) / det : Vec3();
    }
    if (!normals_.empty()) {
        flatNormals_.resize(n);
        for (int i = 0; i < n; ++i) {
            const unsigned* vi = &indices_[3 * i];
            Vec3 a = normals_[vi[0]], b = normals_[vi[1]], c = normals_[vi[2]];
            bool same = a.x == b.x && a.y == b.y && a.z == b.z && a.x == c.x && a.y == c.y && a.z == c.z;
            flatNormals_[i] = same && lengthSquared(a) > 0;
        }
    }
    tangentIsFrameAxis_.assign(n, 0);
    for (int i = 0; i < n; ++i) {
        if (!normals_.empty() && !flatNormals_[i]) continue;  // interpolated: varies over the triangle
        Vec3 ns = normals_.empty() ? faceNormal_[i] : normals_[indices_[3 * i]];
        // Kept only where Frame::fromNormalTangent would not fall back to an arbitrary tangent.
        if (std::optional<Vec3> t = Frame::unitTangent(ns, faceDpdu_[i])) {
            faceDpdu_[i] = *t;
            tangentIsFrameAxis_[i] = 1;
        }
    }
}

RTCGeometry TriangleMesh::buildGeometry(RTCDevice device) const {
    const bool quads = !quads_.sources.empty();
    RTCGeometry g = rtcNewGeometry(device, quads ? RTC_GEOMETRY_TYPE_QUAD : RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions_.data(), 0,
                               3 * sizeof(float), (positions_.size() - 1) / 3);
    if (quads)
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, quads_.quadIndices.data(), 0,
                                   4 * sizeof(unsigned), quads_.sources.size());
    else
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices_.data(), 0,
                                   3 * sizeof(unsigned), indices_.size() / 3);
    installAlphaFilter(g);
    rtcCommitGeometry(g);
    return g;
}


void TriangleMesh::prepareSampling() {
    int n = primitiveCount();
    std::vector<SamplingData> data(n);
    for (int i = 0; i < n; ++i) {
        const unsigned* v = &indices_[3 * i];
        Vec3 p0 = loadP(positions_, v[0]), p1 = loadP(positions_, v[1]), p2 = loadP(positions_, v[2]);
        SamplingData& d = data[i];
        d.p0 = p0;
        d.e1 = p1 - p0;
        d.e2 = p2 - p0;
        d.area = area(i);
        d.n = geometricNormal(i);
        d.normalsMayFlip = false;
        if (!normals_.empty())
            for (int k = 0; k < 3; ++k) d.normalsMayFlip |= dot(normals_[v[k]], d.n) < 0;
        if (!normals_.empty() && !d.normalsMayFlip) {
            // N decides the side; with all vertex normals on one side, so does every point.
            if (dot(normals_[v[0]] + normals_[v[1]] + normals_[v[2]], d.n) < 0) d.n = -d.n;
        }
    }
    sampling_ = std::move(data);
}

// pbrt's default per-triangle parameterisation when a mesh has no uv.
Vec2 TriangleMesh::uvAt(int vertex, int corner) const {
    if (!uv_.empty()) return uv_[vertex];
    return corner == 0 ? Vec2(0, 0) : (corner == 1 ? Vec2(1, 0) : Vec2(1, 1));
}

int TriangleMesh::interaction(const Ray& r, float t, int embreePrim, float u, float v, SurfaceInteraction& si) const {
    int prim = embreePrim;
    if (!quads_.sources.empty()) {
        QuadPairing::TriangleHit h = quads_.triangleHit(embreePrim, u, v);
        prim = h.triangle;
        u = h.u;
        v = h.v;
    }
    const unsigned* vi = &indices_[3 * prim];
    Vec3 p0 = loadP(positions_, vi[0]), p1 = loadP(positions_, vi[1]), p2 = loadP(positions_, vi[2]);
    float b0 = 1 - u - v;
    si.p = p0 * b0 + p1 * u + p2 * v;
    si.t = t;
    (void)r;
    Vec3 ng = faceNormal_[prim];
    si.uv = uv_.empty() ? Vec2(u + v, v) : uv_[vi[0]] * b0 + uv_[vi[1]] * u + uv_[vi[2]] * v;
    Vec3 dpdu = faceDpdu_[prim];

    if (!normals_.empty() && flatNormals_[prim]) {
        si.ns = normals_[vi[0]];  // unit, as normalised at construction
        ng = faceForward(ng, si.ns);
    } else if (!normals_.empty()) {
        Vec3 ns = normals_[vi[0]] * b0 + normals_[vi[1]] * u + normals_[vi[2]] * v;
        float ln = length(ns);
        if (ln > 0) {
            ns = ns / ln;
            ng = faceForward(ng, ns);  // N decides the outside (PBRT-CONVENTIONS §4)
        } else {
            ns = ng;
        }
        si.ns = ns;
    } else {
        si.ns = ng;
    }
    si.ng = ng;
    si.dpdu = dpdu;
    si.tangentIsFrameAxis = tangentIsFrameAxis_[prim];
    if (material && material->needsShadingDerivatives()) shadingDerivatives(prim, si);
    return prim;
}

// As pbrt-v4 builds a triangle's shading geometry: dp/du, dp/dv from the uv parameterisation
// (an arbitrary frame when it is degenerate); with N, the tangent made orthogonal to the
// shading normal, the bitangent n x dp/du, and dn/du, dn/dv from the vertex normals.
void TriangleMesh::shadingDerivatives(int prim, SurfaceInteraction& si) const {
    const unsigned* vi = &indices_[3 * prim];
    Vec3 p0 = loadP(positions_, vi[0]), p1 = loadP(positions_, vi[1]), p2 = loadP(positions_, vi[2]);
    Vec2 duv02 = uvAt(vi[0], 0) - uvAt(vi[2], 2), duv12 = uvAt(vi[1], 1) - uvAt(vi[2], 2);
    Vec3 dp02 = p0 - p2, dp12 = p1 - p2;
    float det = duv02.x * duv12.y - duv02.y * duv12.x;
    bool degenerate = std::fabs(det) < 1e-9f;
    Vec3 dpdu, dpdv;
    if (!degenerate) {
        dpdu = (dp02 * duv12.y - dp12 * duv02.y) / det;
        dpdv = (dp12 * duv02.x - dp02 * duv12.x) / det;
    }
    if (degenerate || lengthSquared(cross(dpdu, dpdv)) == 0) {
        Vec3 n = cross(p2 - p0, p1 - p0);
        if (lengthSquared(n) == 0) return;  // a degenerate triangle: leave the maps inert
        coordinateSystem(normalize(n), dpdu, dpdv);
    }
    si.tangentIsFrameAxis = false;
    if (normals_.empty()) {
        si.dpdu = dpdu;
        si.dpdv = dpdv;
        si.dndu = si.dndv = Vec3();
        return;
    }
    Vec3 ss = dpdu, ts = cross(si.ns, ss);
    if (lengthSquared(ts) > 0) ss = cross(ts, si.ns);
    else coordinateSystem(si.ns, ss, ts);
    si.dpdu = ss;
    si.dpdv = ts;
    const Vec3 &n0 = normals_[vi[0]], &n1 = normals_[vi[1]], &n2 = normals_[vi[2]];
    if (degenerate) {
        Vec3 dn = cross(n2 - n0, n1 - n0);
        if (lengthSquared(dn) == 0) si.dndu = si.dndv = Vec3();
        else coordinateSystem(dn, si.dndu, si.dndv);
    } else {
        Vec3 dn1 = n0 - n2, dn2 = n1 - n2;
        si.dndu = (dn1 * duv12.y - dn2 * duv02.y) / det;
        si.dndv = (dn2 * duv02.x - dn1 * duv12.x) / det;
    }
}

float TriangleMesh::area(int prim) const {
    if (!sampling_.empty()) return sampling_[prim].area;
    const unsigned* v = &indices_[3 * prim];
    Vec3 p0 = loadP(positions_, v[0]), p1 = loadP(positions_, v[1]), p2 = loadP(positions_, v[2]);
    return 0.5f * length(cross(p1 - p0, p2 - p0));
}

ShapeSample TriangleMesh::sampleArea(int prim, Vec2 u) const {
    const unsigned* vi = &indices_[3 * prim];
    Vec3 p0 = loadP(positions_, vi[0]), p1 = loadP(positions_, vi[1]), p2 = loadP(positions_, vi[2]);
    Vec2 b = sampleUniformTriangle(u);
    float b2 = 1 - b.x - b.y;
    ShapeSample s;
    s.p = p0 * b.x + p1 * b.y + p2 * b2;
    Vec3 n = geometricNormal(prim);
    if (!normals_.empty()) {
        Vec3 ns = normals_[vi[0]] * b.x + normals_[vi[1]] * b.y + normals_[vi[2]] * b2;
        if (lengthSquared(ns) > 0) n = faceForward(n, ns);
    }
    s.n = n;
    s.uv = uvAt(vi[0], 0) * b.x + uvAt(vi[1], 1) * b.y + uvAt(vi[2], 2) * b2;
    float a = area(prim);
    s.pdf = a > 0 ? 1.0f / a : 0.0f;
    return s;
}

}  // namespace ps

namespace ps {

// Area sampling converted to solid angle at ref, in one pass (the light-sampling hot path).
std::optional<ShapeSample> TriangleMesh::sampleToward(int prim, Vec3 ref, Vec2 u) const {
    if (sampling_.empty()) return Shape::sampleToward(prim, ref, u);
    const SamplingData& t = sampling_[prim];
    if (t.normalsMayFlip || alpha || emissionNeedsUV) return Shape::sampleToward(prim, ref, u);  // these need uv
    Vec2 b = sampleUniformTriangle(u);  // weights of vertices 0 and 1
    ShapeSample s;
    // p = b0 p0 + b1 p1 + b2 p2 = p0 + b1 e1 + b2 e2.
    s.p = t.p0 + t.e1 * b.y + t.e2 * (1 - b.x - b.y);
    s.n = t.n;
    Vec3 d = s.p - ref;
    float dist2 = lengthSquared(d);
    if (!(dist2 > 0) || !(t.area > 0)) return std::nullopt;
    s.wi = d / std::sqrt(dist2);
    float cosLight = absDot(s.n, s.wi);
    if (!(cosLight > 0)) return std::nullopt;
    s.pdf = dist2 / (cosLight * t.area);
    s.pdfArea = 1 / t.area;
    if (!std::isfinite(s.pdf)) return std::nullopt;
    return s;  // uv is not needed by uniform, unmasked emitters
}

Bounds3 TriangleMesh::primitiveBounds(int prim) const {
    const unsigned* vi = &indices_[3 * prim];
    Bounds3 b(loadP(positions_, vi[0]));
    b.expand(loadP(positions_, vi[1]));
    b.expand(loadP(positions_, vi[2]));
    return b;
}

DirectionCone TriangleMesh::normalBounds(int prim) const {
    Vec3 ng = faceNormal_[prim];
    if (normals_.empty()) return DirectionCone(ng, 1);
    // With N the side of the interpolated normal decides (sampleArea, interaction): one side
    // for the whole triangle when the three vertex normals agree on it.
    const unsigned* vi = &indices_[3 * prim];
    int above = 0, below = 0;
    for (int k = 0; k < 3; ++k) {
        float c = dot(normals_[vi[k]], ng);
        above += c > 0;
        below += c < 0;
    }
    if (above == 3) return DirectionCone(ng, 1);
    if (below == 3) return DirectionCone(-ng, 1);
    return DirectionCone::entireSphere();
}

}  // namespace ps
