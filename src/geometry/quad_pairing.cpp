#include "geometry/quad_pairing.h"

#include <cstddef>

namespace ps {

namespace {

// Weights of a triangle's corners (0, 1, 2) from the weights w of its corners rotated by
// `shift` (w[k] belongs to corner (k + shift) mod 3), returned as Embree's (u, v).
QuadPairing::TriangleHit unrotate(int triangle, int shift, const float w[3]) {
    return {triangle, w[(4 - shift) % 3], w[(5 - shift) % 3]};
}

}  // namespace

QuadPairing::TriangleHit QuadPairing::triangleHit(int quad, float u, float v) const {
    const Source& s = sources[std::size_t(quad)];
    if (s.second < 0 || u + v <= 1) {
        const float w[3] = {1 - u - v, u, v};  // on (v0, v1, v3)
        return unrotate(s.first, s.firstShift, w);
    }
    const float w[3] = {u + v - 1, 1 - u, 1 - v};  // on (v2, v3, v1): Embree's u = 1 - u', v = 1 - v'
    return unrotate(s.second, s.secondShift, w);
}

QuadPairing pairTriangles(const std::vector<unsigned>& indices) {
    QuadPairing q;
    const int n = int(indices.size() / 3);
    auto corner = [&](int tri, int k) { return indices[std::size_t(3 * tri + k % 3)]; };
    int paired = 0;
    for (int i = 0; i < n;) {
        bool done = false;
        if (i + 1 < n) {
            // Rotate triangle i to (x0, x1, x2) = quad (v0, v1, v3); the next triangle must
            // then be a rotation of (v2, x2, x1): the shared edge walked the other way.
            for (int r = 0; r < 3 && !done; ++r) {
                unsigned x0 = corner(i, r), x1 = corner(i, r + 1), x2 = corner(i, r + 2);
                for (int s = 0; s < 3 && !done; ++s) {
                    unsigned y0 = corner(i + 1, s);
                    if (corner(i + 1, s + 1) != x2 || corner(i + 1, s + 2) != x1) continue;
                    if (y0 == x0 || y0 == x1 || y0 == x2 || x0 == x1 || x1 == x2 || x0 == x2) continue;
                    q.quadIndices.insert(q.quadIndices.end(), {x0, x1, y0, x2});
                    q.sources.push_back({i, i + 1, uint8_t(r), uint8_t(s)});
                    done = true;
                }
            }
        }
        if (done) {
            paired += 2;
            i += 2;
        } else {
            q.quadIndices.insert(q.quadIndices.end(), {corner(i, 0), corner(i, 1), corner(i, 2), corner(i, 2)});
            q.sources.push_back({i, -1, 0, 0});
            i += 1;
        }
    }
    if (2 * paired < n) return {};
    return q;
}

}  // namespace ps
