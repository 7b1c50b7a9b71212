// The tiny NanoVDB grid of tests/data/media/tiny.nvdb, written by tests/tools/make_nvdb.cpp
// and read back by the nanovdb reader's tests: a 16^3 float "density" grid at index (0..15)^3,
// seven 8^3 leaves and one constant tile (the block 8..15 in every axis, a tile of the lower
// node), voxel size 1/16, the world box [-0.5, 0.5]^3. The file holds a second grid, "smoke",
// before it, so that a reader must skip grids to find "density".
#pragma once

namespace nvdbtest {

constexpr int kSize = 16;
constexpr float kTileValue = 0.25f;
constexpr float kVoxelSize = 1.0f / 16, kOrigin = -0.5f;  // world = index * kVoxelSize + kOrigin

inline bool inTile(int i, int j, int k) { return i >= 8 && j >= 8 && k >= 8; }

// The density at a voxel of the grid (0 outside it: the background).
inline float value(int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= kSize || j >= kSize || k >= kSize) return 0;
    if (inTile(i, j, k)) return kTileValue;
    // Peaky on purpose (a majorant grid has work to do): mostly thin, a few dense voxels.
    const int h = (i * 7 + j * 13 + k * 29) % 17;
    return h == 0 ? 4.0f : 0.05f * float(h % 5);
}

}  // namespace nvdbtest
