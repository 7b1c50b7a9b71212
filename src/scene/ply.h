// PLY meshes as pbrt-v4's "plymesh" reads them (PBRT-CONVENTIONS §4 "PLY meshes"): positions,
// optional normals and uv, triangles and quads, optional per-face indices.
#pragma once
#include <string>
#include <vector>

#include "math/vec.h"
#include "util/error.h"

namespace ps {

struct PlyMesh {
    std::vector<Vec3> P;            // positions (x y z), required
    std::vector<Vec3> N;            // normals (nx ny nz), empty if absent
    std::vector<Vec2> uv;           // from u v | s t | texture_u texture_v | texture_s texture_t, empty if absent
    std::vector<int> triIndices;    // 3 per triangle
    std::vector<int> quadIndices;   // 4 per quad, in file order v0 v1 v2 v3
    std::vector<int> faceIndices;   // optional per-face "face_indices", empty if absent
};
// Reads ASCII, binary_little_endian and binary_big_endian PLY, optionally gzip-compressed
// (detect the gzip magic bytes 1f 8b, or a .gz suffix; use zlib's gzopen/gzread).
// faceIndices holds one entry per face of the file, skipped faces included, as in pbrt-v4.
// Throws InputError("<path>: <what is wrong>") for missing, malformed, truncated or absurd files.
PlyMesh readPly(const std::string& path);

}  // namespace ps
