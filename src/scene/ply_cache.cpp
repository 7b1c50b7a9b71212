#include "scene/ply_cache.h"

namespace ps {

namespace {

PlyCache* gInUse = nullptr;

}  // namespace

PlyCache::Use::Use(PlyCache& cache) { gInUse = &cache; }
PlyCache::Use::~Use() { gInUse = nullptr; }

PlyMesh readPlyCached(const std::string& path) {
    if (!gInUse) return readPly(path);
    auto it = gInUse->meshes_.find(path);
    if (it == gInUse->meshes_.end()) it = gInUse->meshes_.emplace(path, readPly(path)).first;
    return it->second;
}

}  // namespace ps
