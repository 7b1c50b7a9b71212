// PLY meshes (ASCII and binary, optionally gzipped) as pbrt-v4's plymesh reads them
// (PBRT-CONVENTIONS §4): positions, optional normals and uv, triangles and quads.
#pragma once
#include <string>
#include <vector>
#include "math/vec.h"

namespace ps {

struct PlyMesh {
    std::vector<Vec3> P;            // positions (x y z), required
    std::vector<Vec3> N;            // normals (nx ny nz), empty if absent
    std::vector<Vec2> uv;           // u v | s t | texture_u texture_v | texture_s texture_t
    std::vector<int> triIndices;    // 3 per triangle
    std::vector<int> quadIndices;   // 4 per quad, in file order v0 v1 v2 v3
    std::vector<int> faceIndices;   // optional per-face "face_indices"
};

// Throws InputError("<path>: <what is wrong>") for missing, malformed or truncated files.
PlyMesh readPly(const std::string& path);

}  // namespace ps
