#include "geometry/quad_pairing.h"

namespace ps {

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
