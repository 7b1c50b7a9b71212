// A reader of NanoVDB files (.nvdb) for the float grids pbrt-v4's "nanovdb" medium reads
// (media.cpp: NanoVDBMedium::Create, through nanovdb::io::readGrid). Debian 12 packages
// OpenVDB 10 but not NanoVDB's headers, so the format is read here from its published layout
// (NanoVDB.h and util/IO.h of the version pbrt-v4 pins, file format 32.x):
//   file     = segments; segment = header (magic "NanoVDB0", version, grid count, codec),
//              then each grid's 176-byte metadata and name, then each grid's bytes
//   grid     = GridData (672 B: name, index<->world map, world box, class, type), TreeData
//              (64 B: offsets of the node arrays), the root (a table of tiles keyed by their
//              4096^3 block) and three levels of nodes: upper 32^3 children of 128^3 voxels,
//              lower 16^3 children of 8^3 voxels, leaves of 8^3 float values.
// Grids are uncompressed ("NONE") or zlib-compressed ("ZIP", zlib being a dependency
// already); "BLOSC" is refused with an error saying so. Every offset is checked when the file
// is read, so lookups never leave the buffer; a bad file is an error naming it, never a crash.
#pragma once
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>
#include "math/vec.h"

namespace ps {

class NanoVDBGrid {
public:
    // The value NanoVDB's accessor gives at voxel (i, j, k): a leaf's value, else the value of
    // the tile that covers it, else the background.
    float value(int i, int j, int k) const;
    // The aligned 8^3 block of voxels that (i, j, k) lies in: a leaf's 512 values (x major),
    // or one value for all of them (a tile at any level covers whole blocks, as does the
    // background). Lookups within a block then skip the tree.
    struct Block {
        const uint8_t* leafValues = nullptr;  // null: `value` everywhere in the block
        float value = 0;
        float at(int i, int j, int k) const {
            if (!leafValues) return value;
            float v;
            std::memcpy(&v, leafValues + 4 * ((uint32_t(i & 7) << 6) | (uint32_t(j & 7) << 3) | uint32_t(k & 7)), sizeof v);
            return v;
        }
    };
    Block block(int i, int j, int k) const;
    // Trilinear interpolation of the voxel values, which sit at integer index coordinates
    // (NanoVDB's SampleFromVoxels of order 1).
    float sample(Vec3 pIndex) const;
    // World (the medium's space) to index space by the grid's single-precision inverse map.
    Vec3 worldToIndex(Vec3 p) const;

    const std::string& name() const { return name_; }
    Vec3 worldMin() const { return worldMin_; }
    Vec3 worldMax() const { return worldMax_; }
    const int* indexMin() const { return indexMin_; }  // inclusive
    const int* indexMax() const { return indexMax_; }  // inclusive
    float background() const { return background_; }
    // The largest value stored anywhere (voxels, tiles, background), NaN values aside.
    float maxValue() const { return maxValue_; }
    uint32_t gridClass() const { return gridClass_; }

private:
    friend class NanoVDBParser;
    struct RootTile {
        uint64_t key;
        int64_t upper;  // byte offset of the child upper node in bytes_, or -1: a tile value
        float value;
    };
    Block treeBlock(int i, int j, int k) const;
    Block lowerBlock(size_t lower, int i, int j, int k) const;
    Block upperBlock(size_t upper, int i, int j, int k) const;
    void buildBlockTable();

    std::string name_;
    std::vector<uint8_t> bytes_;
    std::vector<RootTile> tiles_;  // sorted by key
    // Every 8^3 block of the index box, x fastest: the byte offset of its leaf's values, or
    // 0 and its tile's value. A lookup inside the box then costs one load, not a descent of
    // the tree (the root's binary search and three levels). Empty when it would be large.
    struct TableEntry {
        uint32_t leaf;
        float value;
    };
    std::vector<TableEntry> table_;
    int tableMin_[3] = {}, tableRes_[3] = {};  // in blocks
    float invMat_[9] = {}, vec_[3] = {};
    Vec3 worldMin_, worldMax_;
    int indexMin_[3] = {}, indexMax_[3] = {};
    float background_ = 0, maxValue_ = 0;
    uint32_t gridClass_ = 0;
};

// The first grid named `gridName` in `path`; nullopt when the file has no grid of that name.
// Throws std::runtime_error naming the file for a file that cannot be read, is not a NanoVDB
// file, is truncated or inconsistent, or whose grid is not a float grid.
std::optional<NanoVDBGrid> readNanoVDBGrid(const std::string& path, const std::string& gridName);
// The same from bytes in memory (the fuzz target); `what` names them in errors.
std::optional<NanoVDBGrid> parseNanoVDBGrid(const uint8_t* data, size_t size, const std::string& gridName,
                                            const std::string& what);

}  // namespace ps
