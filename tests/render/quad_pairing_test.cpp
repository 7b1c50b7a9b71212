// Triangle meshes traced as Embree quads must report exactly the hits of the triangles:
// same triangle, same distance, same barycentrics, for pairs in every corner rotation,
// non-planar pairs and unpaired triangles.
#include <gtest/gtest.h>

#include <embree3/rtcore.h>

#include "geometry/quad_pairing.h"
#include "geometry/triangle_mesh.h"
#include "math/transform.h"
#include "mc/rng.h"

namespace ps {
namespace {

// Triangle t's corners rotated left by r.
std::vector<int> rotated(std::vector<int> t, int r) {
    std::vector<int> out(3);
    for (int k = 0; k < 3; ++k) out[size_t(k)] = t[size_t((k + r) % 3)];
    return out;
}

// A grid of bent quads, each written as two triangles in one of the 9 corner rotations,
// then one lone triangle, then another quad (pairing resumes after an unpaired triangle).
TriangleMeshData bentQuadGrid(Rng& rng) {
    TriangleMeshData m;
    const int n = 3;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) m.P.push_back({float(x), float(y), 0.3f * rng.uniform()});  // non-planar
    auto id = [&](int x, int y) { return y * (n + 1) + x; };
    int combo = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x, ++combo) {
            int a = id(x, y), b = id(x + 1, y), c = id(x + 1, y + 1), d = id(x, y + 1);
            for (int v : rotated({a, b, d}, combo % 3)) m.indices.push_back(v);
            for (int v : rotated({c, d, b}, combo / 3)) m.indices.push_back(v);
            if (combo == 4) {
                int base = int(m.P.size());
                m.P.push_back({0.2f, 0.1f, 1.0f});
                m.P.push_back({2.5f, 0.4f, 1.2f});
                m.P.push_back({1.0f, 2.7f, 0.9f});
                for (int k = 0; k < 3; ++k) m.indices.push_back(base + k);
            }
        }
    return m;
}

TEST(QuadPairing, PairsEveryRotationAndSkipsLoneTriangles) {
    Rng rng(1);
    TriangleMeshData m = bentQuadGrid(rng);
    std::vector<unsigned> idx(m.indices.begin(), m.indices.end());
    QuadPairing q = pairTriangles(idx);
    ASSERT_EQ(q.sources.size(), 10u);  // 9 quads and one lone triangle
    int lone = 0;
    for (const QuadPairing::Source& s : q.sources) lone += s.second < 0;
    EXPECT_EQ(lone, 1);

    // Mostly unpaired: triangles (0 1 2), (3 4 5), ... share no edge.
    std::vector<unsigned> scattered;
    for (unsigned i = 0; i < 12; ++i) scattered.push_back(i);
    EXPECT_TRUE(pairTriangles(scattered).sources.empty());
}

TEST(QuadPairing, QuadHitsAreTheTriangleHits) {
    Rng rng(7);
    TriangleMeshData data = bentQuadGrid(rng);
    std::vector<Vec3> P = data.P;
    std::vector<unsigned> idx(data.indices.begin(), data.indices.end());
    TriangleMesh mesh(data, Transform(), false);

    RTCDevice device = rtcNewDevice(nullptr);
    RTCScene quads = rtcNewScene(device), tris = rtcNewScene(device);
    RTCGeometry gq = mesh.buildGeometry(device);
    rtcAttachGeometry(quads, gq);
    rtcReleaseGeometry(gq);
    rtcCommitScene(quads);
    std::vector<float> pos;
    for (Vec3 p : P) pos.insert(pos.end(), {p.x, p.y, p.z});
    pos.push_back(0);
    RTCGeometry gt = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(gt, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, pos.data(), 0, 12, P.size());
    rtcSetSharedGeometryBuffer(gt, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, idx.data(), 0, 12, idx.size() / 3);
    rtcCommitGeometry(gt);
    rtcAttachGeometry(tris, gt);
    rtcReleaseGeometry(gt);
    rtcCommitScene(tris);

    auto trace = [](RTCScene s, Vec3 o, Vec3 d) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh{};
        rh.ray.org_x = o.x; rh.ray.org_y = o.y; rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x; rh.ray.dir_y = d.y; rh.ray.dir_z = d.z;
        rh.ray.tnear = 0;
        rh.ray.tfar = 1e30f;
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(s, &ctx, &rh);
        return rh;
    };
    int hits = 0, lone = 0;
    for (int i = 0; i < 20000; ++i) {
        // From above and below, aimed at random points over the grid.
        Vec3 target{-0.2f + 3.4f * rng.uniform(), -0.2f + 3.4f * rng.uniform(), 0.5f * rng.uniform()};
        Vec3 o{3 * rng.uniform(), 3 * rng.uniform(), rng.uniform() < 0.5f ? -2.0f : 3.0f};
        Vec3 d = normalize(target - o);
        RTCRayHit a = trace(quads, o, d), b = trace(tris, o, d);
        ASSERT_EQ(a.hit.geomID == RTC_INVALID_GEOMETRY_ID, b.hit.geomID == RTC_INVALID_GEOMETRY_ID) << i;
        if (b.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        ++hits;
        EXPECT_NEAR(a.ray.tfar, b.ray.tfar, 1e-5f * b.ray.tfar);
        SurfaceInteraction si;
        int prim = mesh.interaction(Ray{o, d}, a.ray.tfar, int(a.hit.primID), a.hit.u, a.hit.v, si);
        lone += prim == 10;  // the lone triangle follows the first five quads
        // On a shared edge either triangle is right; the point must agree regardless.
        const unsigned* v = &idx[3 * b.hit.primID];
        Vec3 pRef = P[v[0]] * (1 - b.hit.u - b.hit.v) + P[v[1]] * b.hit.u + P[v[2]] * b.hit.v;
        EXPECT_LT(length(si.p - pRef), 1e-4f) << i;
        bool onEdge = std::min({b.hit.u, b.hit.v, 1 - b.hit.u - b.hit.v}) < 1e-4f;
        if (!onEdge) {
            EXPECT_EQ(prim, int(b.hit.primID)) << i;
            EXPECT_NEAR(si.uv.x, b.hit.u + b.hit.v, 1e-4f);  // pbrt's default uv: (u + v, v)
            EXPECT_NEAR(si.uv.y, b.hit.v, 1e-4f);
        }
    }
    EXPECT_GT(hits, 10000);
    EXPECT_GT(lone, 100);
    rtcReleaseScene(quads);
    rtcReleaseScene(tris);
    rtcReleaseDevice(device);
}

}  // namespace
}  // namespace ps
