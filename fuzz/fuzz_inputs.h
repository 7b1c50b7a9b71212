// How the fuzz targets turn bytes into reader calls, shared by the libFuzzer targets and by
// the regression test that replays their findings (tests/render/fuzz_regressions_test.cpp).
// Each function returns normally on success or InputError (the expected failure for bad input);
// anything else escapes or crashes. The readers take paths and scenes resolve Include/Import on
// disk, so inputs are written to files in a private scratch directory first.
#pragma once
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <climits>
#include <string>
#include <string_view>

#include "image/image.h"
#include "media/nanovdb_file.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "scene/ply.h"
#include "util/error.h"
#include "util/memory_limit.h"

namespace ps::fuzz {

// Every input runs under a small memory limit, so that the fuzzer spends its time on parsing,
// not on decoding legitimate-but-huge images (a 5 KB JPEG can claim 90 Mpixels: at a 64 MiB
// limit the image target ran 90 inputs/s, nearly all of it in the instrumented pixel loops),
// and so that the limit's own error path is fuzzed too: 4 MiB for scenes and meshes, 256 KiB
// (16 K pixels) for images, whose header and segment parsing is what can go wrong. Set per
// input and restored after it, because the regression test replays these inputs inside a test
// process whose other tests keep the default limit.
constexpr uint64_t kFuzzMemoryLimit = uint64_t(4) << 20;
constexpr uint64_t kFuzzImageMemoryLimit = uint64_t(256) << 10;

// One directory per process, reused for every input and removed at exit. A plain array, not
// a std::string: the atexit handler runs after static objects are destroyed.
inline std::string scratchDir() {
    static char dir[] = "/tmp/ps-fuzz-XXXXXX";
    static const bool made = [] {
        if (!mkdtemp(dir)) std::abort();
        std::atexit([] { (void)!std::system((std::string("rm -rf '") + dir + "'").c_str()); });
        return true;
    }();
    (void)made;
    return dir;
}

inline std::string writeScratchFile(const std::string& name, std::string_view bytes) {
    std::string path = scratchDir() + "/" + name;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size()) std::abort();
    std::fclose(f);
    return path;
}

inline void removeScratchFile(const std::string& name) { std::remove((scratchDir() + "/" + name).c_str()); }

// Up to three files separated by the marker line "#--file--": main.pbrt, include.pbrt and
// mesh.ply, so that Include, Import and plymesh of generated files resolve. Parsed, then built.
inline void runSceneInput(const uint8_t* data, size_t size) {
    ScopedMemoryLimit limit(kFuzzMemoryLimit);
    static const char* const kNames[] = {"main.pbrt", "include.pbrt", "mesh.ply"};
    constexpr std::string_view kMarker = "#--file--\n";
    std::string_view rest(reinterpret_cast<const char*>(data), size);
    bool more = true;
    std::string mainPath;
    for (int i = 0; i < 3; ++i) {
        if (!more) {
            removeScratchFile(kNames[i]);  // absent: exercises the missing-file errors
            continue;
        }
        size_t cut = i < 2 ? rest.find(kMarker) : std::string_view::npos;
        std::string path = writeScratchFile(kNames[i], rest.substr(0, cut));
        if (i == 0) mainPath = path;
        more = cut != std::string_view::npos;
        if (more) rest = rest.substr(cut + kMarker.size());
    }
    try {
        SceneDescription desc = parseSceneFile(mainPath);
        buildScene(desc);
    } catch (const InputError&) {
    }
}

// Arbitrary bytes as a PLY file; the reader sniffs the gzip magic itself.
inline void runPlyInput(const uint8_t* data, size_t size) {
    ScopedMemoryLimit limit(kFuzzMemoryLimit);
    std::string path = writeScratchFile("mesh.ply", {reinterpret_cast<const char*>(data), size});
    try {
        readPly(path);
    } catch (const InputError&) {
    }
}

// The first byte picks the extension (.png .jpg .tga .exr .hdr .pfm: readers fall back on it
// when the content is not recognised) and the PNG colour encoding; the rest is the file.
inline void runImageInput(const uint8_t* data, size_t size) {
    if (size == 0) return;
    ScopedMemoryLimit limit(kFuzzImageMemoryLimit);
    static const char* const kExtensions[] = {".png", ".jpg", ".tga", ".exr", ".hdr", ".pfm"};
    std::string name = std::string("image") + kExtensions[(data[0] & 0x7f) % 6];
    auto encoding = (data[0] & 0x80) ? ColorEncoding::Linear : ColorEncoding::SRGB;
    std::string path = writeScratchFile(name, {reinterpret_cast<const char*>(data + 1), size - 1});
    try {
        readImage(path, encoding);
    } catch (const InputError&) {
    }
    removeScratchFile(name);
}

// The bytes are a NanoVDB file, read from memory; its "density" grid, if any, is then looked
// up at voxels around its index box and sampled between them. The reader's failure for bad
// input is a runtime_error naming the file (media/nanovdb_file.h).
inline void runNanoVDBInput(const uint8_t* data, size_t size) {
    try {
        std::optional<NanoVDBGrid> g = parseNanoVDBGrid(data, size, "density", "fuzz.nvdb");
        if (!g) return;
        float sum = 0;
        for (int64_t a = -1; a <= 1; ++a)
            for (int c = 0; c < 8; ++c) {
                auto at = [&](int axis, bool high) {  // a voxel just inside or outside the index box
                    const int64_t v = high ? int64_t(g->indexMax()[axis]) + a : int64_t(g->indexMin()[axis]) - a;
                    return int(std::clamp<int64_t>(v, INT32_MIN, INT32_MAX));
                };
                const int i = at(0, c & 1), j = at(1, c & 2), k = at(2, c & 4);
                sum += g->value(i, j, k) + g->sample(Vec3(float(i) + 0.5f, float(j) + 0.25f, float(k) + 0.75f));
            }
        (void)sum;
    } catch (const std::runtime_error&) {
    }
}

}  // namespace ps::fuzz
