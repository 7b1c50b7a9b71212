#include "geometry/loop_subdivision.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

namespace ps {

namespace {

using Tri = std::array<int, 3>;
constexpr int next(int i) { return (i + 1) % 3; }
constexpr int prev(int i) { return (i + 2) % 3; }

int vnum(const Tri& t, int v) { return t[0] == v ? 0 : t[1] == v ? 1 : 2; }

// Adjacency of one level of the mesh and every vertex's one-ring in pbrt-v4's order
// (SDVertex::oneRing): interior vertices start anywhere and walk across the edge
// (v, next vertex) from face to face; boundary vertices start at the end of that walk and
// go back the other way, so ring[0] and ring[n-1] are the two boundary neighbours.
struct Connectivity {
    std::vector<std::array<int, 3>> across;  // per face and edge k = (v[k], v[k+1]): the face on its other side, or -1
    std::vector<int> ringStart;              // vertex v's ring is ringVerts[ringStart[v] .. ringStart[v+1])
    std::vector<int> ringVerts;
    std::vector<uint8_t> boundary;
    size_t valence(int v) const { return size_t(ringStart[v + 1] - ringStart[v]); }
    const int* ring(int v) const { return ringVerts.data() + ringStart[v]; }
};

uint64_t edgeKey(int a, int b) { return a < b ? (uint64_t(a) << 32 | uint32_t(b)) : (uint64_t(b) << 32 | uint32_t(a)); }

Connectivity connect(const std::vector<Tri>& faces, size_t nVertices) {
    Connectivity c;
    c.across.assign(faces.size(), {-1, -1, -1});
    struct Open {
        int face, edge, uses;
    };
    std::unordered_map<uint64_t, Open> edges;
    edges.reserve(faces.size() * 2);
    std::vector<int> startFace(nVertices, -1), faceCount(nVertices, 0);
    for (int f = 0; f < int(faces.size()); ++f) {
        for (int k = 0; k < 3; ++k) {
            const int a = faces[f][k], b = faces[f][next(k)];
            startFace[a] = f;
            ++faceCount[a];
            auto [it, inserted] = edges.try_emplace(edgeKey(a, b), Open{f, k, 1});
            if (inserted) continue;
            Open& o = it->second;
            if (++o.uses > 2)
                throw std::invalid_argument("the edge between vertices " + std::to_string(a) + " and " + std::to_string(b) +
                                            " belongs to more than two triangles (Loop subdivision needs a manifold mesh)");
            if (faces[o.face][next(o.edge)] != a)
                throw std::invalid_argument("triangles " + std::to_string(o.face) + " and " + std::to_string(f) +
                                            " traverse their shared edge in the same direction (inconsistent winding)");
            c.across[f][k] = o.face;
            c.across[o.face][o.edge] = f;
        }
    }
    c.ringStart.assign(nVertices + 1, 0);
    c.boundary.assign(nVertices, 0);
    c.ringVerts.reserve(faces.size() * 3 + nVertices);
    auto fan = [&](int v) {
        throw std::invalid_argument("the triangles around vertex " + std::to_string(v) +
                                    " do not form a single fan (Loop subdivision needs a manifold mesh)");
    };
    for (int v = 0; v < int(nVertices); ++v) {
        c.ringStart[v] = int(c.ringVerts.size());
        int start = startFace[v];
        if (start < 0) continue;  // unused: no ring, dropped from the result
        // Walk across (v, next) edges: back at the start for an interior vertex.
        int f = start, visited = 0;
        do {
            f = c.across[f][vnum(faces[f], v)];
            if (++visited > faceCount[v]) fan(v);
        } while (f >= 0 && f != start);
        if (f == start) {
            visited = 0;
            do {
                const int k = vnum(faces[f], v);
                c.ringVerts.push_back(faces[f][next(k)]);
                f = c.across[f][k];
                ++visited;
            } while (f != start);
        } else {
            c.boundary[v] = 1;
            f = start;
            for (int g; (g = c.across[f][vnum(faces[f], v)]) >= 0;) f = g;
            c.ringVerts.push_back(faces[f][next(vnum(faces[f], v))]);
            visited = 0;
            do {
                const int k = vnum(faces[f], v);
                c.ringVerts.push_back(faces[f][prev(k)]);
                f = c.across[f][prev(k)];
                if (++visited > faceCount[v]) fan(v);
            } while (f >= 0);
        }
        if (visited != faceCount[v]) fan(v);
    }
    c.ringStart[nVertices] = int(c.ringVerts.size());
    return c;
}

// Loop's even-vertex weight (pbrt-v4's beta(); Warren's 3/16 for valence 3).
double beta(size_t n) { return n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * double(n)); }
// The weight that moves a vertex of valence n to its limit position.
double limitGamma(size_t n) { return 1.0 / (double(n) + 3.0 / (8.0 * beta(n))); }

// (1 - n w) p + w * sum of the ring: the interior rules.
Vec3 oneRingRule(const Connectivity& c, const std::vector<Vec3>& P, int v, double w) {
    const size_t n = c.valence(v);
    const int* r = c.ring(v);
    double x = (1 - double(n) * w) * P[v].x, y = (1 - double(n) * w) * P[v].y, z = (1 - double(n) * w) * P[v].z;
    for (size_t i = 0; i < n; ++i) {
        x += w * P[r[i]].x;
        y += w * P[r[i]].y;
        z += w * P[r[i]].z;
    }
    return Vec3(float(x), float(y), float(z));
}

// (1 - 2w) p + w (both boundary neighbours): the crease rules.
Vec3 boundaryRule(const Connectivity& c, const std::vector<Vec3>& P, int v, float w) {
    const int* r = c.ring(v);
    return (1 - 2 * w) * P[v] + w * P[r[0]] + w * P[r[c.valence(v) - 1]];
}

Vec3 vertexRule(const Connectivity& c, const std::vector<Vec3>& P, int v, bool limit) {
    if (c.valence(v) == 0) return P[v];
    if (c.boundary[v]) return boundaryRule(c, P, v, limit ? 1.f / 5.f : 1.f / 8.f);
    return oneRingRule(c, P, v, limit ? limitGamma(c.valence(v)) : beta(c.valence(v)));
}

// Limit-surface normal S x T from the tangents of the one-ring (pbrt-v4's weights).
Vec3 limitNormal(const Connectivity& c, const std::vector<Vec3>& P, int v) {
    const int n = int(c.valence(v));
    const int* r = c.ring(v);
    const Vec3 p = P[v];
    Vec3 S(0, 0, 0), T(0, 0, 0);
    if (!c.boundary[v]) {
        for (int j = 0; j < n; ++j) {
            const double a = 2 * 3.14159265358979323846 * j / n;
            S += float(std::cos(a)) * P[r[j]];
            T += float(std::sin(a)) * P[r[j]];
        }
    } else {
        S = P[r[n - 1]] - P[r[0]];
        if (n == 2) {
            T = P[r[0]] + P[r[1]] - 2 * p;
        } else if (n == 3) {
            T = P[r[1]] - p;
        } else if (n == 4) {
            T = -1 * P[r[0]] + 2 * P[r[1]] + 2 * P[r[2]] - P[r[3]] - 2 * p;
        } else {
            const double theta = 3.14159265358979323846 / (n - 1);
            T = float(std::sin(theta)) * (P[r[0]] + P[r[n - 1]]);
            for (int k = 1; k < n - 1; ++k) T += float((2 * std::cos(theta) - 2) * std::sin(k * theta)) * P[r[k]];
            T = -T;
        }
    }
    Vec3 N = cross(S, T);
    const float l = length(N);
    return l > 0 ? N / l : Vec3(0, 0, 0);
}

}  // namespace

TriangleMeshData loopSubdivide(int levels, const std::vector<int>& indices, const std::vector<Vec3>& P0) {
    std::vector<Vec3> P = P0;
    std::vector<Tri> faces(indices.size() / 3);
    for (size_t f = 0; f < faces.size(); ++f) {
        faces[f] = {indices[3 * f], indices[3 * f + 1], indices[3 * f + 2]};
        if (faces[f][0] == faces[f][1] || faces[f][1] == faces[f][2] || faces[f][2] == faces[f][0])
            throw std::invalid_argument("triangle " + std::to_string(f) + " uses one vertex twice");
    }
    for (int level = 0; level < levels; ++level) {
        const Connectivity c = connect(faces, P.size());
        // Even vertices keep their indices; each edge's odd vertex follows them.
        std::vector<Vec3> newP(P.size());
        for (int v = 0; v < int(P.size()); ++v) newP[v] = vertexRule(c, P, v, false);
        std::vector<std::array<int, 3>> edgeVertex(faces.size(), {-1, -1, -1});
        for (int f = 0; f < int(faces.size()); ++f) {
            for (int k = 0; k < 3; ++k) {
                if (edgeVertex[f][k] >= 0) continue;
                const int a = faces[f][k], b = faces[f][next(k)], g = c.across[f][k];
                edgeVertex[f][k] = int(newP.size());
                if (g < 0) {
                    newP.push_back(0.5f * P[a] + 0.5f * P[b]);
                } else {
                    const int kg = vnum(faces[g], b);  // g traverses the edge as (b, a)
                    edgeVertex[g][kg] = edgeVertex[f][k];
                    newP.push_back(3.f / 8.f * P[a] + 3.f / 8.f * P[b] + 1.f / 8.f * P[faces[f][prev(k)]] +
                                   1.f / 8.f * P[faces[g][prev(kg)]]);
                }
            }
        }
        // Four children per triangle, wound as their parent (pbrt-v4's children 0..3).
        std::vector<Tri> newFaces;
        newFaces.reserve(faces.size() * 4);
        for (int f = 0; f < int(faces.size()); ++f) {
            const Tri& t = faces[f];
            const int e01 = edgeVertex[f][0], e12 = edgeVertex[f][1], e20 = edgeVertex[f][2];
            newFaces.push_back({t[0], e01, e20});
            newFaces.push_back({e01, t[1], e12});
            newFaces.push_back({e20, e12, t[2]});
            newFaces.push_back({e01, e12, e20});
        }
        P = std::move(newP);
        faces = std::move(newFaces);
    }

    // Push every vertex to the limit surface, then take the normals from the limit ring.
    const Connectivity c = connect(faces, P.size());
    std::vector<Vec3> limit(P.size());
    for (int v = 0; v < int(P.size()); ++v) limit[v] = vertexRule(c, P, v, true);
    TriangleMeshData out;
    std::vector<int> remap(P.size(), -1);
    for (int v = 0; v < int(P.size()); ++v) {
        if (c.valence(v) == 0) continue;
        remap[v] = int(out.P.size());
        out.P.push_back(limit[v]);
        out.N.push_back(limitNormal(c, limit, v));
    }
    out.indices.reserve(faces.size() * 3);
    for (const Tri& t : faces)
        for (int v : t) out.indices.push_back(remap[v]);
    return out;
}

}  // namespace ps
