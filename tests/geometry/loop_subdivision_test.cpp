// Loop subdivision (Shape "loopsubdiv") against answers computed here from the control mesh
// alone: Loop's closed-form limit positions, the cubic B-spline of a boundary, and the mesh's
// topology.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>

#include "geometry/loop_subdivision.h"

using namespace ps;

namespace {

struct Mesh {
    std::vector<Vec3> P;
    std::vector<int> indices;
};

// Regular tetrahedron around the origin, wound counter-clockwise seen from outside.
Mesh tetrahedron() { return {{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}, {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2}}; }

// The cube [-1,1]^3, its faces split along diagonals chosen so that its vertices have
// valences 3, 4, 5 and 6, wound counter-clockwise seen from outside.
Mesh cube() {
    Mesh m;
    for (int i = 0; i < 8; ++i) m.P.push_back(Vec3(i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f));
    const int quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (int f = 0; f < 6; ++f) {
        const int* q = quads[f];
        const int k = f == 5 ? 1 : 0;  // which diagonal
        for (int t : {q[k], q[k + 1], q[k + 2], q[k], q[k + 2], q[(k + 3) % 4]}) m.indices.push_back(t);
    }
    for (size_t t = 0; t < m.indices.size(); t += 3) {  // orient each triangle outward
        Vec3 a = m.P[m.indices[t]], b = m.P[m.indices[t + 1]], c = m.P[m.indices[t + 2]];
        if (dot(cross(b - a, c - a), a + b + c) < 0) std::swap(m.indices[t + 1], m.indices[t + 2]);
    }
    return m;
}

Mesh reversed(Mesh m) {
    for (size_t t = 0; t < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
    return m;
}

std::set<int> neighbours(const Mesh& m, int v) {
    std::set<int> n;
    for (size_t t = 0; t < m.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k)
            if (m.indices[t + k] == v) {
                n.insert(m.indices[t + (k + 1) % 3]);
                n.insert(m.indices[t + (k + 2) % 3]);
            }
    return n;
}

// Loop's limit position of an interior vertex of valence n from its control ring:
// (1 - n g) p + g sum(ring), g = 1 / (n + 3 / (8 beta)), the left eigenvector of the
// subdivision matrix for pbrt-v4's weights beta = 3/16 (n = 3) or 3 / (8n).
Vec3 closedFormLimit(const Mesh& m, int v) {
    std::set<int> ring = neighbours(m, v);
    const double n = double(ring.size());
    const double beta = ring.size() == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n);
    const double g = 1.0 / (n + 3.0 / (8.0 * beta));
    Vec3 sum(0, 0, 0);
    for (int r : ring) sum += m.P[r];
    return float(1 - n * g) * m.P[v] + float(g) * sum;
}

void expectNear(Vec3 a, Vec3 b, float tol, const std::string& what) {
    EXPECT_LT(length(a - b), tol) << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y
                                  << ", " << b.z << ")";
}

// Every edge is shared by exactly two triangles that traverse it in opposite directions.
void expectWatertight(const TriangleMeshData& d) {
    std::map<std::pair<int, int>, int> directed;
    for (size_t t = 0; t < d.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) ++directed[{d.indices[t + k], d.indices[t + (k + 1) % 3]}];
    for (const auto& [e, count] : directed) {
        EXPECT_EQ(count, 1) << e.first << "-" << e.second;
        EXPECT_EQ(directed.count({e.second, e.first}), 1u) << e.first << "-" << e.second << " is a boundary edge";
    }
}

}  // namespace

// The original vertices of a closed mesh end at Loop's closed-form limit points, at every
// level (the limit does not depend on where the push to the limit happens): this checks the
// even and odd rules, which move the control points, as well as the limit weights.
TEST(LoopSubdivision, ClosedMeshesReachLoopsLimitPoints) {
    for (const auto& [name, mesh] : {std::pair{"tetrahedron", tetrahedron()}, std::pair{"cube", cube()}}) {
        std::printf("  %s valences:", name);
        for (int v = 0; v < int(mesh.P.size()); ++v) std::printf(" %zu", neighbours(mesh, v).size());
        std::printf("\n");
        for (int levels = 0; levels <= 4; ++levels) {
            TriangleMeshData d = loopSubdivide(levels, mesh.indices, mesh.P);
            ASSERT_EQ(d.indices.size(), mesh.indices.size() << (2 * levels)) << name << " at " << levels << " levels";
            ASSERT_EQ(d.N.size(), d.P.size());
            double worst = 0;
            for (int v = 0; v < int(mesh.P.size()); ++v) {
                Vec3 expected = closedFormLimit(mesh, v);
                worst = std::max(worst, double(length(d.P[v] - expected)));
                expectNear(d.P[v], expected, 1e-5f, std::string(name) + " vertex " + std::to_string(v) + " at " + std::to_string(levels));
            }
            std::printf("  %s, %d levels: %zu triangles, largest distance to the closed-form limit %.2g\n", name, levels,
                        d.indices.size() / 3, worst);
            expectWatertight(d);
        }
    }
    // The regular tetrahedron's corners: (2/5) p + (1/5) (-p) = p / 5.
    TriangleMeshData d = loopSubdivide(3, tetrahedron().indices, tetrahedron().P);
    for (int v = 0; v < 4; ++v) expectNear(d.P[v], tetrahedron().P[v] / 5, 1e-6f, "tetrahedron corner");
}

// Unit limit normals, on the side pbrt-v4 puts them: the one-ring runs clockwise seen from
// where the winding normal points, so N = S x T is the negated winding normal (a
// counter-clockwise closed mesh gets inward normals; checked by rendering with pbrt-v4).
TEST(LoopSubdivision, LimitNormalsAreUnitAndOppositeTheWinding) {
    for (const auto& [name, mesh] : {std::pair{"tetrahedron", tetrahedron()}, std::pair{"cube", cube()}}) {
        for (int flip = 0; flip < 2; ++flip) {
            Mesh m = flip ? reversed(mesh) : mesh;
            TriangleMeshData d = loopSubdivide(3, m.indices, m.P);
            double minCos = 1;
            for (size_t v = 0; v < d.P.size(); ++v) {
                EXPECT_NEAR(length(d.N[v]), 1.f, 1e-5f) << name << " vertex " << v;
                // Convex around the origin: the outward direction is the radial one.
                minCos = std::min(minCos, double(dot(d.N[v], normalize(d.P[v]))) * (flip ? 1 : -1));
            }
            std::printf("  %s (%s winding): smallest cosine between N and the expected side %.3f\n", name,
                        flip ? "clockwise" : "counter-clockwise", minCos);
            EXPECT_GT(minCos, 0.5) << name;
            // Also each triangle's winding normal against its vertices' N.
            for (size_t t = 0; t < d.indices.size(); t += 3) {
                Vec3 a = d.P[d.indices[t]], b = d.P[d.indices[t + 1]], c = d.P[d.indices[t + 2]];
                EXPECT_LT(dot(cross(b - a, c - a), d.N[d.indices[t]]), 0) << name << " triangle " << t / 3;
            }
        }
    }
    // By symmetry the tetrahedron's corners have exactly radial normals.
    TriangleMeshData d = loopSubdivide(2, tetrahedron().indices, tetrahedron().P);
    for (int v = 0; v < 4; ++v) expectNear(d.N[v], -normalize(tetrahedron().P[v]), 1e-5f, "corner normal");
}

// An open mesh: the crease rules make its boundary a cubic B-spline of the boundary polygon
// alone. The 1-D curve subdivided here (even (1 6 1)/8, odd (1 1)/2, then pbrt-v4's limit
// mask (1 3 1)/5) must reappear in the mesh, whatever lies inside the boundary.
TEST(LoopSubdivision, BoundaryFollowsTheBoundaryCurve) {
    const std::vector<Vec3> polygon = {{0, 0, 0}, {1, 0, 0.5f}, {1, 1, 0}, {0, 1, 0.3f}};
    const Mesh quad{polygon, {0, 1, 2, 0, 2, 3}};
    Mesh fan{polygon, {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4}};
    fan.P.push_back(Vec3(0.5f, 0.5f, 2));
    for (int levels = 1; levels <= 4; ++levels) {
        std::vector<Vec3> curve = polygon;
        for (int l = 0; l < levels; ++l) {
            std::vector<Vec3> finer;
            const size_t n = curve.size();
            for (size_t i = 0; i < n; ++i) {
                Vec3 p = curve[i], before = curve[(i + n - 1) % n], after = curve[(i + 1) % n];
                finer.push_back((before + 6 * p + after) / 8);
                finer.push_back((p + after) / 2);
            }
            curve = finer;
        }
        std::vector<Vec3> limit;
        const size_t n = curve.size();
        for (size_t i = 0; i < n; ++i) limit.push_back((3 * curve[i] + curve[(i + n - 1) % n] + curve[(i + 1) % n]) / 5);
        for (const auto& [name, mesh] : {std::pair{"quad", quad}, std::pair{"fan", fan}}) {
            TriangleMeshData d = loopSubdivide(levels, mesh.indices, mesh.P);
            ASSERT_EQ(d.indices.size(), mesh.indices.size() << (2 * levels));
            for (size_t i = 0; i < limit.size(); ++i) {
                float nearest = 1e30f;
                for (Vec3 p : d.P) nearest = std::min(nearest, length(p - limit[i]));
                EXPECT_LT(nearest, 1e-5f) << name << ", " << levels << " levels: curve point " << i;
            }
            for (int v = 0; v < 4; ++v) expectNear(d.P[v], limit[size_t(v) << levels], 1e-5f, std::string(name) + " corner");
            for (Vec3 N : d.N) EXPECT_NEAR(length(N), 1.f, 1e-5f) << name;
        }
        // pbrt-v4's (1 3 1)/5 is not the B-spline's limit mask (1 4 1)/6: the corners approach
        // the true limit curve as the levels grow (by the subdominant eigenvalue 1/4).
        double off = 0;
        for (int v = 0; v < 4; ++v)
            off = std::max(off, double(length(limit[size_t(v) << levels] - (polygon[(v + 3) % 4] + 4 * polygon[v] + polygon[(v + 1) % 4]) / 6)));
        std::printf("  %d levels: corners within %.2g of the exact B-spline limit\n", levels, off);
        EXPECT_LT(off, 0.1 / double(1 << (2 * levels)));
    }
}

// The limit normals are normal to the surface: nearly perpendicular to every edge at a
// vertex once the mesh is fine, on interior and boundary vertices (whose tangents use
// pbrt-v4's separate boundary masks) alike, and opposite each triangle's winding normal.
TEST(LoopSubdivision, LimitNormalsAreNormalToTheSurface) {
    const std::vector<Vec3> polygon = {{0, 0, 0}, {1, 0, 0.5f}, {1, 1, 0}, {0, 1, 0.3f}};
    Mesh fan{polygon, {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4}};
    fan.P.push_back(Vec3(0.5f, 0.5f, 0.6f));
    // A strip whose boundary vertices have valences 2 to 5 (one to four triangles).
    Mesh strip{{{0, 0, 0}, {1, 0, 0.2f}, {2, 0, 0}, {3, 0, 0.3f}, {0, 1, 0.1f}, {1, 1, 0}, {2, 1, 0.4f}, {3, 1, 0}},
               {0, 1, 5, 0, 5, 4, 1, 2, 5, 2, 6, 5, 2, 7, 6, 2, 3, 7}};
    // The bound on |cos| (the angle the normal makes with the true tangent plane, deterministic)
    // is looser for the closed meshes, which are more curved at this level.
    struct Case {
        const char* name;
        Mesh mesh;
        double bound;
    };
    for (const auto& [name, mesh, bound] : {Case{"tetrahedron", tetrahedron(), 0.15}, Case{"cube", cube(), 0.15},
                                            Case{"open fan", fan, 0.1}, Case{"open strip", strip, 0.1}}) {
        TriangleMeshData d = loopSubdivide(5, mesh.indices, mesh.P);
        double worst = 0;
        for (size_t t = 0; t < d.indices.size(); t += 3) {
            for (int k = 0; k < 3; ++k) {
                int v = d.indices[t + k], w = d.indices[t + (k + 1) % 3], x = d.indices[t + (k + 2) % 3];
                worst = std::max(worst, double(std::fabs(dot(d.N[v], normalize(d.P[w] - d.P[v])))));
                EXPECT_LT(dot(cross(d.P[w] - d.P[v], d.P[x] - d.P[v]), d.N[v]), 0) << name << " triangle " << t / 3;
            }
        }
        std::printf("  %s, 5 levels: largest |cos| between a vertex normal and an edge at it %.3f\n", name, worst);
        EXPECT_LT(worst, bound) << name;
    }
}

TEST(LoopSubdivision, RefusesNonManifoldInput) {
    const std::vector<Vec3> P = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {-1, 0, 0}, {0, -1, 0}};
    auto error = [&](const std::vector<int>& indices) {
        try {
            loopSubdivide(1, indices, P);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(error({0, 1, 2, 1, 0, 3, 0, 1, 4}).find("more than two"), std::string::npos);  // three triangles on edge 0-1
    EXPECT_NE(error({0, 1, 2, 0, 1, 3}).find("same direction"), std::string::npos);         // inconsistent winding
    EXPECT_NE(error({0, 1, 2, 0, 5, 6}).find("single fan"), std::string::npos);             // a bow tie at vertex 0
    EXPECT_NE(error({0, 0, 2}).find("twice"), std::string::npos);
    // Unused vertices are dropped; the rest keep their order.
    TriangleMeshData d = loopSubdivide(0, {1, 3, 2}, P);
    EXPECT_EQ(d.P.size(), 3u);
    EXPECT_EQ(d.indices, (std::vector<int>{0, 2, 1}));
}
