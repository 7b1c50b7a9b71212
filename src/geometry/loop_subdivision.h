// Shape "loopsubdiv": Loop subdivision of a triangle mesh as pbrt-v4 performs it
// (util/loopsubdiv.cpp), turned into a TriangleMesh for the ordinary mesh path.
#pragma once
#include <string>
#include <vector>
#include "geometry/triangle_mesh.h"

namespace ps {

// Subdivides the triangles `indices` over `P` `levels` times with Loop's rules (interior
// vertices: the one-ring rule with beta = 3/16 for valence 3, else 3/(8n); boundary
// vertices and edges: the crease rules 3/4,1/8,1/8 and 1/2,1/2), then moves every vertex
// to its limit position and gives it pbrt-v4's limit normal N = S x T from the tangents of
// its one-ring. Each level multiplies the triangle count by 4. Vertices no triangle uses
// are dropped; the others come first in the result, in their input order. Throws std::invalid_argument (the message says what is wrong) for an edge
// shared by more than two triangles, an edge two triangles traverse in the same direction,
// or a vertex whose triangles form more than one fan: Loop's rules need a manifold,
// consistently oriented mesh.
//
// Pitfall (as pbrt-v4; checked with a pbrt-v4 build): the one-ring runs clockwise as seen
// from the side the winding normal points to, so N is the *negated* winding normal, and
// with N given the surface's outside follows N (PBRT-CONVENTIONS §4). A mesh wound counter-
// clockwise seen from outside thus emits, as an area light, towards its inside.
TriangleMeshData loopSubdivide(int levels, const std::vector<int>& indices, const std::vector<Vec3>& P);

}  // namespace ps
