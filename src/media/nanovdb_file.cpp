#include "media/nanovdb_file.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <unordered_set>

namespace ps {

namespace {

// The layout of NanoVDB 32.x (pbrt-v4's pinned NanoVDB 32.3), in bytes.
constexpr uint64_t kMagic = 0x304244566f6e614eULL;  // "NanoVDB0" little-endian
constexpr uint32_t kMajorVersion = 32;
constexpr size_t kHeaderSize = 16, kMetaSize = 176;
constexpr size_t kGridDataSize = 672, kTreeDataSize = 64;
constexpr size_t kRootHeaderSize = 64, kRootTileSize = 32;
// Internal nodes: bbox and flags (32 B), value mask, child mask, four statistics, then a
// 32-byte aligned table of 8-byte entries (a float tile value or a signed child offset).
constexpr size_t kUpperChildMask = 32 + 4096, kUpperTable = 8256, kUpperSize = 270400;
constexpr size_t kLowerChildMask = 32 + 512, kLowerTable = 1088, kLowerSize = 33856;
constexpr size_t kLeafValues = 96, kLeafSize = 2144;
constexpr uint32_t kGridTypeFloat = 1;
constexpr uint32_t kGridClassUnknown = 0, kGridClassFogVolume = 2;
constexpr uint16_t kCodecNone = 0, kCodecZip = 1, kCodecBlosc = 2;
// zlib cannot inflate by more than about 1032:1, so a larger claimed size is a corrupt header.
constexpr uint64_t kMaxZipRatio = 1100;

template <typename T>
T load(const uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

bool bitOn(const uint8_t* mask, uint32_t n) { return (load<uint64_t>(mask + 8 * (n >> 6)) >> (n & 63)) & 1; }

// Random access to the file's bytes, from a file or from memory.
struct Source {
    std::function<bool(uint64_t offset, uint64_t n, void* dst)> read;
    uint64_t size = 0;
};

}  // namespace

class NanoVDBParser {
public:
    NanoVDBParser(const Source& src, std::string what) : src_(src), what_(std::move(what)) {}

    std::optional<NanoVDBGrid> find(const std::string& gridName) {
        uint64_t pos = 0;
        while (pos < src_.size) {
            uint8_t header[kHeaderSize];
            need(pos, kHeaderSize, header, "segment header");
            const uint64_t magic = load<uint64_t>(header);
            if (magic != kMagic) {
                if (pos == 0) fail("not a NanoVDB file (no \"NanoVDB0\" magic number at its start)");
                fail("a segment at byte " + std::to_string(pos) + " has no \"NanoVDB0\" magic number");
            }
            const uint32_t version = load<uint32_t>(header + 8);
            if (version >> 21 != kMajorVersion)
                fail("NanoVDB file format version " + std::to_string(version >> 21) + "." + std::to_string((version >> 10) & 2047) +
                     " is not supported (version " + std::to_string(kMajorVersion) + ".x is, as in pbrt-v4)");
            const uint16_t gridCount = load<uint16_t>(header + 12), codec = load<uint16_t>(header + 14);
            pos += kHeaderSize;
            struct Meta {
                uint64_t gridSize, fileSize;
                uint32_t gridType, gridClass;
                std::string name;
            };
            std::vector<Meta> metas;
            for (int g = 0; g < gridCount; ++g) {
                uint8_t m[kMetaSize];
                need(pos, kMetaSize, m, "grid metadata");
                Meta meta{load<uint64_t>(m), load<uint64_t>(m + 8), load<uint32_t>(m + 32), load<uint32_t>(m + 36), {}};
                const uint32_t nameSize = load<uint32_t>(m + 136);
                pos += kMetaSize;
                if (nameSize > src_.size - std::min(src_.size, pos)) fail("truncated: a grid name runs past the end of the file");
                std::string name(nameSize, '\0');
                need(pos, nameSize, name.data(), "grid name");
                meta.name = name.substr(0, name.find('\0'));
                pos += nameSize;
                metas.push_back(std::move(meta));
            }
            for (const Meta& meta : metas) {
                if (meta.fileSize > src_.size - std::min(src_.size, pos))
                    fail("truncated: grid \"" + meta.name + "\" needs " + std::to_string(meta.fileSize) + " bytes at byte " +
                         std::to_string(pos) + " of a " + std::to_string(src_.size) + "-byte file");
                if (meta.name == gridName) return grid(meta.gridSize, meta.fileSize, meta.gridType, meta.gridClass, codec, pos, gridName);
                pos += meta.fileSize;
            }
        }
        return std::nullopt;
    }

private:
    [[noreturn]] void fail(const std::string& msg) const { throw std::runtime_error(what_ + ": " + msg); }

    void need(uint64_t pos, uint64_t n, void* dst, const char* what) const {
        if (pos > src_.size || n > src_.size - pos || !src_.read(pos, n, dst))
            fail(std::string("truncated: the file ends inside the ") + what + " at byte " + std::to_string(pos));
    }

    NanoVDBGrid grid(uint64_t gridSize, uint64_t fileSize, uint32_t type, uint32_t cls, uint16_t codec, uint64_t pos,
                     const std::string& name) {
        const std::string g = "grid \"" + name + "\"";
        if (type != kGridTypeFloat)
            fail(g + " holds values of NanoVDB grid type " + std::to_string(type) + ", not float (type 1)");
        if (cls != kGridClassFogVolume && cls != kGridClassUnknown)
            fail(g + " is of grid class " + std::to_string(cls) + ", not a fog volume (pbrt-v4 reads fog volumes only)");
        if (gridSize < kGridDataSize + kTreeDataSize + kRootHeaderSize) fail(g + " is too small to hold a grid");
        NanoVDBGrid out;
        out.name_ = name;
        if (codec == kCodecBlosc)
            fail(g + " is compressed with Blosc, which pathspace cannot read; write it uncompressed (nanovdb_convert without --blosc) or with --zip");
        if (codec == kCodecNone) {
            if (gridSize != fileSize) fail(g + "'s sizes in memory and on disk differ in an uncompressed file");
            out.bytes_.resize(gridSize);
            need(pos, gridSize, out.bytes_.data(), "grid");
        } else if (codec == kCodecZip) {
            uint64_t zipSize = 0;
            need(pos, 8, &zipSize, "compressed grid");
            if (zipSize > fileSize - std::min<uint64_t>(fileSize, 8)) fail(g + "'s compressed size exceeds its size on disk");
            if (gridSize / kMaxZipRatio > zipSize) fail(g + " claims more bytes than its compressed data can hold");
            std::vector<uint8_t> zipped(zipSize);
            need(pos + 8, zipSize, zipped.data(), "compressed grid");
            out.bytes_.resize(gridSize);
            uLongf got = uLongf(gridSize);
            if (uncompress(out.bytes_.data(), &got, zipped.data(), uLong(zipSize)) != Z_OK || got != gridSize)
                fail(g + "'s ZIP (zlib) data are corrupt or of the wrong size");
        } else {
            fail(g + " uses unknown compression codec " + std::to_string(codec));
        }
        index(out, g);
        return out;
    }

    // Reads the grid's header fields and checks every node reachable from the root.
    void index(NanoVDBGrid& out, const std::string& g) const {
        const std::vector<uint8_t>& b = out.bytes_;
        const size_t size = b.size();
        if (load<uint64_t>(b.data()) != kMagic) fail(g + " does not start with the NanoVDB magic number");
        if (load<uint32_t>(b.data() + 636) != kGridTypeFloat) fail(g + "'s own header says it is not a float grid");
        out.gridClass_ = load<uint32_t>(b.data() + 632);
        for (int i = 0; i < 9; ++i) out.invMat_[i] = load<float>(b.data() + 332 + 4 * i);
        for (int i = 0; i < 3; ++i) out.vec_[i] = load<float>(b.data() + 368 + 4 * i);
        double box[6];
        std::memcpy(box, b.data() + 560, sizeof box);
        out.worldMin_ = Vec3(float(box[0]), float(box[1]), float(box[2]));
        out.worldMax_ = Vec3(float(box[3]), float(box[4]), float(box[5]));
        for (double v : box)
            if (!std::isfinite(v)) fail(g + "'s world bounding box is not finite");
        for (float v : out.invMat_)
            if (!std::isfinite(v)) fail(g + "'s index-to-world map is not invertible");
        const uint64_t rootOffset = load<uint64_t>(b.data() + kGridDataSize + 24);
        const size_t root = kGridDataSize + rootOffset;
        if (rootOffset > size || root > size - kRootHeaderSize) fail(g + ": the root node lies outside the grid");
        for (int a = 0; a < 3; ++a) {
            out.indexMin_[a] = load<int32_t>(b.data() + root + 4 * a);
            out.indexMax_[a] = load<int32_t>(b.data() + root + 12 + 4 * a);
        }
        const uint32_t tableSize = load<uint32_t>(b.data() + root + 24);
        out.background_ = load<float>(b.data() + root + 28);
        if (tableSize > (size - root - kRootHeaderSize) / kRootTileSize) fail(g + ": the root's tile table runs past the grid's end");
        std::unordered_set<size_t> seen;
        float& mx = out.maxValue_;
        mx = out.background_;
        for (uint32_t t = 0; t < tableSize; ++t) {
            const size_t tile = root + kRootHeaderSize + t * kRootTileSize;
            const int64_t child = load<int64_t>(b.data() + tile + 8);
            NanoVDBGrid::RootTile rt{load<uint64_t>(b.data() + tile), -1, load<float>(b.data() + tile + 20)};
            if (child != 0) {
                rt.upper = int64_t(checkedChild(root, child, kUpperSize, size, g, "an upper node"));
                checkUpper(b, size_t(rt.upper), seen, g, mx);
            } else {
                mx = std::max(mx, rt.value);
            }
            out.tiles_.push_back(rt);
        }
        std::sort(out.tiles_.begin(), out.tiles_.end(), [](const auto& x, const auto& y) { return x.key < y.key; });
        out.buildBlockTable();
    }

    size_t checkedChild(size_t parent, int64_t offset, size_t childSize, size_t size, const std::string& g, const char* what) const {
        const int64_t at = int64_t(parent) + offset;
        if (offset == 0 || at < 0 || uint64_t(at) > size || size - uint64_t(at) < childSize)
            fail(g + ": " + what + " lies outside the grid (a corrupt child offset)");
        return size_t(at);
    }

    // Checks the children of an upper node and theirs, and raises `mx` to every value stored
    // below it (tile values and leaf values): a bound for cells too large to scan.
    void checkUpper(const std::vector<uint8_t>& b, size_t upper, std::unordered_set<size_t>& seen, const std::string& g,
                    float& mx) const {
        if (!seen.insert(upper).second) return;
        for (uint32_t n = 0; n < 32768; ++n) {
            if (!bitOn(b.data() + upper + kUpperChildMask, n)) {
                mx = std::max(mx, load<float>(b.data() + upper + kUpperTable + 8 * n));
                continue;
            }
            const size_t lower = checkedChild(upper, load<int64_t>(b.data() + upper + kUpperTable + 8 * n), kLowerSize, b.size(), g, "a lower node");
            if (!seen.insert(lower).second) continue;
            for (uint32_t m = 0; m < 4096; ++m) {
                if (!bitOn(b.data() + lower + kLowerChildMask, m)) {
                    mx = std::max(mx, load<float>(b.data() + lower + kLowerTable + 8 * m));
                    continue;
                }
                const size_t leaf = checkedChild(lower, load<int64_t>(b.data() + lower + kLowerTable + 8 * m), kLeafSize, b.size(), g, "a leaf");
                if (!seen.insert(leaf).second) continue;
                for (uint32_t v = 0; v < 512; ++v) mx = std::max(mx, load<float>(b.data() + leaf + kLeafValues + 4 * v));
            }
        }
    }

    const Source& src_;
    std::string what_;
};

// Lookups: the root's tile of the 4096^3 block, then the upper node's slot of 128^3 voxels,
// the lower node's slot of 8^3, the leaf's voxel; x is the major index at every level.
NanoVDBGrid::Block NanoVDBGrid::lowerBlock(size_t lower, int i, int j, int k) const {
    const uint32_t n = (uint32_t((i & 127) >> 3) << 8) | (uint32_t((j & 127) >> 3) << 4) | uint32_t((k & 127) >> 3);
    const uint8_t* entry = bytes_.data() + lower + kLowerTable + 8 * n;
    if (!bitOn(bytes_.data() + lower + kLowerChildMask, n)) return {nullptr, load<float>(entry)};
    return {bytes_.data() + size_t(int64_t(lower) + load<int64_t>(entry)) + kLeafValues, 0};
}

NanoVDBGrid::Block NanoVDBGrid::upperBlock(size_t upper, int i, int j, int k) const {
    const uint32_t n = (uint32_t((i & 4095) >> 7) << 10) | (uint32_t((j & 4095) >> 7) << 5) | uint32_t((k & 4095) >> 7);
    const uint8_t* entry = bytes_.data() + upper + kUpperTable + 8 * n;
    if (!bitOn(bytes_.data() + upper + kUpperChildMask, n)) return {nullptr, load<float>(entry)};
    return lowerBlock(size_t(int64_t(upper) + load<int64_t>(entry)), i, j, k);
}

void NanoVDBGrid::buildBlockTable() {
    int64_t n = 1;
    for (int a = 0; a < 3; ++a) {
        if (indexMax_[a] < indexMin_[a]) return;  // no active voxel
        tableMin_[a] = indexMin_[a] >> 3;  // floor division: the shift is arithmetic
        tableRes_[a] = (indexMax_[a] >> 3) - tableMin_[a] + 1;
        n *= tableRes_[a];
        if (n > int64_t(1) << 24) return;  // (a corrupt box may be 2^29 blocks a side)
    }
    // At most an eighth of the grid's own bytes (a sparse grid's box may hold many empty
    // blocks), and offsets that fit in 32 bits.
    if (n * int64_t(sizeof(TableEntry)) > int64_t(bytes_.size() / 8) || bytes_.size() >> 32) return;
    table_.resize(size_t(n));
    size_t e = 0;
    for (int z = 0; z < tableRes_[2]; ++z)
        for (int y = 0; y < tableRes_[1]; ++y)
            for (int x = 0; x < tableRes_[0]; ++x, ++e) {
                const Block b = treeBlock((tableMin_[0] + x) * 8, (tableMin_[1] + y) * 8, (tableMin_[2] + z) * 8);
                table_[e] = {b.leafValues ? uint32_t(b.leafValues - bytes_.data()) : 0u, b.value};
            }
}

NanoVDBGrid::Block NanoVDBGrid::block(int i, int j, int k) const {
    if (!table_.empty()) {
        const uint32_t x = uint32_t((i >> 3) - tableMin_[0]), y = uint32_t((j >> 3) - tableMin_[1]), z = uint32_t((k >> 3) - tableMin_[2]);
        if (x < uint32_t(tableRes_[0]) && y < uint32_t(tableRes_[1]) && z < uint32_t(tableRes_[2])) {
            const TableEntry& t = table_[(size_t(z) * tableRes_[1] + y) * tableRes_[0] + x];
            return t.leaf ? Block{bytes_.data() + t.leaf, 0} : Block{nullptr, t.value};
        }
    }
    return treeBlock(i, j, k);
}

NanoVDBGrid::Block NanoVDBGrid::treeBlock(int i, int j, int k) const {
    // The root's key packs the 4096^3 block's coordinates, 21 bits each, z lowest.
    const uint64_t key = uint64_t(uint32_t(k) >> 12) | (uint64_t(uint32_t(j) >> 12) << 21) | (uint64_t(uint32_t(i) >> 12) << 42);
    auto it = std::lower_bound(tiles_.begin(), tiles_.end(), key, [](const RootTile& t, uint64_t k) { return t.key < k; });
    if (it == tiles_.end() || it->key != key) return {nullptr, background_};
    if (it->upper < 0) return {nullptr, it->value};
    return upperBlock(size_t(it->upper), i, j, k);
}

float NanoVDBGrid::value(int i, int j, int k) const { return block(i, j, k).at(i, j, k); }

float NanoVDBGrid::sample(Vec3 p) const {
    // Far outside any grid (or NaN, from a corrupt map): the background, before int overflows.
    const float kFar = float(1 << 30);
    if (!(std::abs(p.x) < kFar && std::abs(p.y) < kFar && std::abs(p.z) < kFar)) return background_;
    const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
    const int i = int(fx), j = int(fy), k = int(fz);
    const float u = p.x - fx, v = p.y - fy, w = p.z - fz;
    auto lerp = [](float a, float b, float t) { return a + t * (b - a); };
    // The eight corners share one 8^3 block unless the cell straddles a block's face (a
    // fifth of lookups, spread evenly): one descent of the tree for them all.
    const bool oneBlock = (i & 7) != 7 && (j & 7) != 7 && (k & 7) != 7;
    const Block b = oneBlock ? block(i, j, k) : Block{};
    auto at = [&](int x, int y, int z) { return oneBlock ? b.at(x, y, z) : value(x, y, z); };
    // Along z, then y, then x, as NanoVDB's trilinear sampler (the same rounding).
    auto alongZ = [&](int di, int dj) { return lerp(at(i + di, j + dj, k), at(i + di, j + dj, k + 1), w); };
    return lerp(lerp(alongZ(0, 0), alongZ(0, 1), v), lerp(alongZ(1, 0), alongZ(1, 1), v), u);
}

Vec3 NanoVDBGrid::worldToIndex(Vec3 p) const {
    const float x = p.x - vec_[0], y = p.y - vec_[1], z = p.z - vec_[2];
    const float* m = invMat_;
    return {m[0] * x + m[1] * y + m[2] * z, m[3] * x + m[4] * y + m[5] * z, m[6] * x + m[7] * y + m[8] * z};
}

std::optional<NanoVDBGrid> parseNanoVDBGrid(const uint8_t* data, size_t size, const std::string& gridName, const std::string& what) {
    Source src{[&](uint64_t offset, uint64_t n, void* dst) {
                   if (n) std::memcpy(dst, data + offset, n);
                   return true;
               },
               size};
    return NanoVDBParser(src, what).find(gridName);
}

std::optional<NanoVDBGrid> readNanoVDBGrid(const std::string& path, const std::string& gridName) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open the file (" + std::strerror(errno) + ")");
    in.seekg(0, std::ios::end);
    const std::streamoff end = in.tellg();
    if (end < 0) throw std::runtime_error(path + ": cannot read the file's size");
    Source src{[&](uint64_t offset, uint64_t n, void* dst) {
                   in.clear();
                   in.seekg(std::streamoff(offset));
                   in.read(static_cast<char*>(dst), std::streamsize(n));
                   return bool(in);
               },
               uint64_t(end)};
    return NanoVDBParser(src, path).find(gridName);
}

}  // namespace ps
