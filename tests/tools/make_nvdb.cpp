// Writes tests/data/media/tiny.nvdb (tests/tools/nvdb_test_grid.h describes it) in NanoVDB's
// file format 32.3, the version pbrt-v4 pins, without NanoVDB itself (Debian 12 has no
// package of it). Usage: make_nvdb OUT.nvdb [zip]. "zip" writes the grids zlib-compressed
// (codec ZIP), to test that path of the reader. `make_nvdb OUT.nvdb cloud N` writes instead
// one "density" grid of N^3 voxels (N a multiple of 8 up to 128), a procedural cloud in the world box
// [-0.5, 0.5]^3 (bench/media_vs_pbrt.py loads it in both renderers).
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tools/nvdb_test_grid.h"

namespace {

using Bytes = std::vector<uint8_t>;

template <typename T>
void put(Bytes& b, size_t at, T v) {
    std::memcpy(b.data() + at, &v, sizeof(T));
}
void setBit(Bytes& b, size_t mask, uint32_t n) {
    uint64_t w;
    std::memcpy(&w, b.data() + mask + 8 * (n >> 6), 8);
    w |= uint64_t(1) << (n & 63);
    std::memcpy(b.data() + mask + 8 * (n >> 6), &w, 8);
}

constexpr uint64_t kMagic = 0x304244566f6e614eULL;
constexpr uint32_t kVersion = (32u << 21) | (3u << 10) | 3u;
// Sizes and offsets of NanoVDB 32.3's float grid (see src/media/nanovdb_file.cpp).
constexpr size_t kGrid = 672, kTree = 64, kRootHeader = 64, kTile = 32;
constexpr size_t kUpper = 270400, kLower = 33856, kLeaf = 2144;

// NanoVDB's name hash (util/IO.h stringHash): h = 67 h + c + (h >> 56) over the bytes.
uint64_t nameHash(const std::string& s) {
    uint64_t h = 0;
    for (unsigned char c : s) h = h * 67 + c + (h >> 56);
    return h;
}

// A grid over index (0..n-1)^3, n <= 128 (one root tile, one upper and one lower node), with
// `value` at each voxel except where `tile` says a whole 8^3 block is a constant; world =
// index * voxel + kOrigin.
template <typename Value, typename TileFn>
Bytes grid(const std::string& name, int n, Value&& value, TileFn&& tile, float tileValue,
           float voxel = nvdbtest::kVoxelSize) {
    std::vector<int> leaves;  // lower-node slot of each leaf
    int tiles = 0;
    const int blocks = (n + 7) / 8;
    for (int a = 0; a < blocks; ++a)
        for (int b = 0; b < blocks; ++b)
            for (int c = 0; c < blocks; ++c) {
                if (tile(8 * a, 8 * b, 8 * c)) ++tiles;
                else leaves.push_back((a << 8) | (b << 4) | c);
            }
    const size_t tree = kGrid, root = tree + kTree, upper = root + kRootHeader + kTile, lower = upper + kUpper,
                 leaf0 = lower + kLower, size = leaf0 + leaves.size() * kLeaf;
    Bytes g(size, 0);
    // GridData
    put(g, 0, kMagic);
    put(g, 8, ~uint64_t(0));  // no checksum
    put(g, 16, kVersion);
    put(g, 28, uint32_t(1));  // grid count
    put(g, 32, uint64_t(size));
    std::memcpy(g.data() + 40, name.c_str(), name.size() + 1);
    const float s = voxel, o = nvdbtest::kOrigin;
    for (int i = 0; i < 3; ++i) {
        put(g, 296 + 4 * (4 * i), s);           // mMatF diagonal
        put(g, 332 + 4 * (4 * i), 1 / s);       // mInvMatF
        put(g, 368 + 4 * i, o);                 // mVecF
        put(g, 384 + 8 * (4 * i), double(s));   // mMatD
        put(g, 456 + 8 * (4 * i), double(1 / s));
        put(g, 528 + 8 * i, double(o));
        put(g, 560 + 8 * i, double(o));                 // world box min: index 0
        put(g, 584 + 8 * i, double(o + s * n));         // max: index n (the last voxel's far side)
        put(g, 608 + 8 * i, double(s));                 // voxel size
    }
    put(g, 552, 1.0);          // taper
    put(g, 380, 1.0f);
    put(g, 632, uint32_t(2));  // fog volume
    put(g, 636, uint32_t(1));  // float
    // TreeData: offsets from the tree of the first leaf, lower, upper node and the root.
    put(g, tree + 0, uint64_t(leaves.empty() ? 0 : leaf0 - tree));
    put(g, tree + 8, uint64_t(lower - tree));
    put(g, tree + 16, uint64_t(upper - tree));
    put(g, tree + 24, uint64_t(root - tree));
    put(g, tree + 32, uint32_t(leaves.size()));
    put(g, tree + 36, uint32_t(1));
    put(g, tree + 40, uint32_t(1));
    put(g, tree + 44, uint32_t(tiles));
    put(g, tree + 56, uint64_t(n) * n * n);
    // Root: index box, one tile (key 0) whose child is the upper node; background 0.
    for (int a = 0; a < 3; ++a) put(g, root + 12 + 4 * a, int32_t(n - 1));
    put(g, root + 24, uint32_t(1));
    put(g, root + kRootHeader + 8, int64_t(upper - root));
    // Upper node: slot 0 is the lower node.
    for (int a = 0; a < 3; ++a) put(g, upper + 12 + 4 * a, int32_t(n - 1));
    setBit(g, upper + 32 + 4096, 0);
    setBit(g, upper + 32, 0);
    put(g, upper + 8256, int64_t(lower - upper));
    // Lower node: leaves and the constant tiles.
    for (int a = 0; a < 3; ++a) put(g, lower + 12 + 4 * a, int32_t(n - 1));
    for (int a = 0; a < blocks; ++a)
        for (int b = 0; b < blocks; ++b)
            for (int c = 0; c < blocks; ++c)
                if (tile(8 * a, 8 * b, 8 * c)) {
                    const uint32_t slot = (a << 8) | (b << 4) | c;
                    setBit(g, lower + 32, slot);  // an active tile
                    put(g, lower + 1088 + 8 * slot, tileValue);
                }
    for (size_t l = 0; l < leaves.size(); ++l) {
        const uint32_t slot = leaves[l];
        const size_t at = leaf0 + l * kLeaf;
        setBit(g, lower + 32 + 512, slot);
        put(g, lower + 1088 + 8 * slot, int64_t(at - lower));
        const int ox = 8 * int(slot >> 8), oy = 8 * int((slot >> 4) & 15), oz = 8 * int(slot & 15);
        put(g, at + 0, int32_t(ox));
        put(g, at + 4, int32_t(oy));
        put(g, at + 8, int32_t(oz));
        for (int a = 0; a < 3; ++a) g[at + 12 + a] = 7;
        float mn = 1e30f, mx = -1e30f;
        for (uint32_t v = 0; v < 512; ++v) {
            const float x = value(ox + int(v >> 6), oy + int((v >> 3) & 7), oz + int(v & 7));
            setBit(g, at + 16, v);
            put(g, at + 96 + 4 * v, x);
            mn = std::min(mn, x);
            mx = std::max(mx, x);
        }
        put(g, at + 80, mn);
        put(g, at + 84, mx);
    }
    return g;
}

// A grid that is a single active root tile of constant `v` (4096^3 voxels, no nodes).
Bytes constantGrid(const std::string& name, float v) {
    Bytes g = grid(name, 8, [](int, int, int) { return 0.0f; }, [](int, int, int) { return true; }, 0);
    const size_t root = kGrid + kTree;
    g.resize(root + kRootHeader + kTile);
    put(g, 32, uint64_t(g.size()));
    for (int i = 0; i < 3; ++i) put(g, 584 + 8 * i, double(nvdbtest::kOrigin + nvdbtest::kVoxelSize * 4096));
    for (size_t at : {size_t(kGrid), size_t(kGrid + 8), size_t(kGrid + 16)}) put(g, at, uint64_t(0));  // no nodes
    for (size_t at = kGrid + 32; at < kGrid + 56; at += 4) put(g, at, uint32_t(0));
    put(g, kGrid + 52, uint32_t(1));  // one active tile, at the root
    for (int a = 0; a < 3; ++a) put(g, root + 12 + 4 * a, int32_t(4095));
    put(g, root + kRootHeader + 8, int64_t(0));
    put(g, root + kRootHeader + 16, uint32_t(1));
    put(g, root + kRootHeader + 20, v);
    return g;
}

// The bench's cloud: a few overlapping soft blobs eroded by value noise (4 octaves), 0 outside,
// over index (0..n-1)^3.
float cloudValue(int n, int i, int j, int k) {
    auto hash = [](int x, int y, int z) {
        uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u ^ uint32_t(z) * 83492791u;
        h ^= h >> 13;
        h *= 0x5bd1e995u;
        h ^= h >> 15;
        return float(h & 0xffffff) / float(0xffffff);
    };
    auto noise = [&](float x, float y, float z) {  // trilinear value noise
        const int x0 = int(std::floor(x)), y0 = int(std::floor(y)), z0 = int(std::floor(z));
        const float fx = x - x0, fy = y - y0, fz = z - z0;
        float v = 0;
        for (int c = 0; c < 8; ++c) {
            const int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
            v += hash(x0 + dx, y0 + dy, z0 + dz) * (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz);
        }
        return v;
    };
    const float x = (i + 0.5f) / n - 0.5f, y = (j + 0.5f) / n - 0.5f, z = (k + 0.5f) / n - 0.5f;
    const float blobs[4][4] = {  // centre, radius
        {0, -0.07f, 0, 0.42f}, {0.22f, 0.05f, 0.06f, 0.27f}, {-0.22f, 0.02f, -0.07f, 0.27f}, {0.05f, 0.2f, -0.03f, 0.25f}};
    float shape = 0;
    for (const auto& b : blobs) {
        const float d2 = ((x - b[0]) * (x - b[0]) + (y - b[1]) * (y - b[1]) + (z - b[2]) * (z - b[2])) / (b[3] * b[3]);
        shape = std::max(shape, 1 - d2);
    }
    if (shape <= 0) return 0;
    float f = 0, amp = 0.5f, freq = 6;
    for (int o = 0; o < 4; ++o, amp *= 0.5f, freq *= 2) f += amp * noise(x * freq + 11, y * freq + 23, z * freq + 37);
    return std::max(0.0f, 2.5f * (shape - 0.55f * f));
}

}  // namespace

int main(int argc, char** argv) {
    const bool cloud = argc > 2 && std::string(argv[2]) == "cloud";
    const int cloudSize = cloud && argc > 3 ? std::atoi(argv[3]) : 0;
    if (argc < 2 || (cloud && (cloudSize < 8 || cloudSize > 128 || cloudSize % 8 != 0))) {
        std::fprintf(stderr, "usage: make_nvdb OUT.nvdb [zip]  or  make_nvdb OUT.nvdb cloud N (N a multiple of 8, 8 to 128)\n");
        return 2;
    }
    const bool zip = argc > 2 && std::string(argv[2]) == "zip";
    std::vector<std::pair<std::string, Bytes>> grids;
    if (cloud) {
        const int n = cloudSize;
        auto value = [n](int i, int j, int k) { return cloudValue(n, i, j, k); };
        auto empty = [&](int i0, int j0, int k0) {  // a block of zeros is a constant tile of 0
            for (int i = i0; i < i0 + 8; ++i)
                for (int j = j0; j < j0 + 8; ++j)
                    for (int k = k0; k < k0 + 8; ++k)
                        if (value(i, j, k) != 0) return false;
            return true;
        };
        grids.emplace_back("density", grid("density", n, value, empty, 0.0f, 1.0f / n));
    } else {
        grids.emplace_back("smoke", constantGrid("smoke", 0.5f));
        grids.emplace_back("density", grid("density", nvdbtest::kSize, nvdbtest::value, nvdbtest::inTile, nvdbtest::kTileValue));
    }
    Bytes out(16, 0);
    put(out, 0, kMagic);
    put(out, 8, kVersion);
    put(out, 12, uint16_t(grids.size()));
    put(out, 14, uint16_t(zip ? 1 : 0));
    std::vector<Bytes> onDisk;
    for (auto& [name, g] : grids) {
        Bytes d;
        if (!zip) {
            d = g;
        } else {
            uLongf n = compressBound(uLong(g.size()));
            d.resize(8 + n);
            if (compress(d.data() + 8, &n, g.data(), uLong(g.size())) != Z_OK) return 1;
            d.resize(8 + n);
            put(d, 0, uint64_t(n));
        }
        Bytes meta(176, 0);
        put(meta, 0, uint64_t(g.size()));
        put(meta, 8, uint64_t(d.size()));
        put(meta, 16, nameHash(name));
        put(meta, 32, uint32_t(1));
        put(meta, 36, uint32_t(2));
        std::memcpy(meta.data() + 40, g.data() + 560, 48);   // world box
        std::memcpy(meta.data() + 88, g.data() + 672 + 64, 24);  // index box (the root's)
        std::memcpy(meta.data() + 112, g.data() + 608, 24);  // voxel size
        put(meta, 136, uint32_t(name.size() + 1));
        put(meta, 168, uint16_t(zip ? 1 : 0));
        put(meta, 172, kVersion);
        out.insert(out.end(), meta.begin(), meta.end());
        out.insert(out.end(), name.c_str(), name.c_str() + name.size() + 1);
        onDisk.push_back(std::move(d));
    }
    for (const Bytes& d : onDisk) out.insert(out.end(), d.begin(), d.end());
    FILE* f = std::fopen(argv[1], "wb");
    if (!f || std::fwrite(out.data(), 1, out.size(), f) != out.size() || std::fclose(f) != 0) {
        std::perror(argv[1]);
        return 1;
    }
    std::printf("%s: %zu bytes\n", argv[1], out.size());
    return 0;
}
