// Triangle meshes handed to Embree as quads. Exporters write quads as two consecutive
// triangles sharing an edge; Embree's quad primitive is exactly such a pair (triangles
// v0,v1,v3 and v2,v3,v1, any planarity), and a BVH over half as many primitives traces
// faster. The pairing changes nothing geometric: every hit maps back to the triangle it
// lies on and that triangle's own barycentrics.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ps {

struct QuadPairing {
    // One quad per entry: (v0, v1, v2, v3) in Embree's order; an unpaired triangle (a, b, c)
    // is the degenerate quad (a, b, c, c), whose second triangle has no area.
    std::vector<unsigned> quadIndices;
    struct Source {
        int first, second;             // triangle of (v0, v1, v3) and of (v2, v3, v1); second = -1 if none
        uint8_t firstShift, secondShift;  // rotation from the triangle's corners to the quad's
    };
    std::vector<Source> sources;

    // The triangle an Embree quad hit (u, v) lies on, and its barycentrics (weights of the
    // triangle's corners 1 and 2, as Embree reports for triangles).
    struct TriangleHit {
        int triangle;
        float u, v;
    };
    TriangleHit triangleHit(int quad, float u, float v) const {
        const Source& s = sources[std::size_t(quad)];
        if (s.second < 0 || u + v <= 1) return unrotate(s.first, s.firstShift, 1 - u - v, u, v);  // on (v0, v1, v3)
        return unrotate(s.second, s.secondShift, u + v - 1, 1 - u, 1 - v);  // on (v2, v3, v1): u = 1 - u', v = 1 - v'
    }

private:
    // A triangle's (u, v) from the weights w0..w2 of its corners rotated by `shift` (wk
    // belongs to corner (k + shift) mod 3).
    static TriangleHit unrotate(int triangle, int shift, float w0, float w1, float w2) {
        switch (shift) {
            case 0: return {triangle, w1, w2};
            case 1: return {triangle, w0, w1};
            default: return {triangle, w2, w0};
        }
    }
};

// Pairs consecutive triangles (2k, 2k+1 after any unpaired one) that share an edge with
// opposite directions; returns an empty pairing when fewer than half the triangles pair, as
// a quad BVH of mostly degenerate quads would be slower. `indices`: 3 per triangle.
QuadPairing pairTriangles(const std::vector<unsigned>& indices);

}  // namespace ps
