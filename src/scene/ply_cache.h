// Meshes kept between builds of one scene: while a PlyCache is in use, the scene builder reads
// each PLY file once and copies it from memory after, so the Python module rebuilds a scene
// after an override (resolution, camera, material, light) without reading its meshes again.
#pragma once
#include <map>
#include <string>

#include "scene/ply.h"

namespace ps {

class PlyCache {
public:
    // Makes `cache` the one readPlyCached uses (one at a time, process-wide) for its lifetime.
    class Use {
    public:
        explicit Use(PlyCache& cache);
        ~Use();
        Use(const Use&) = delete;
        Use& operator=(const Use&) = delete;
    };

private:
    friend PlyMesh readPlyCached(const std::string& path);
    std::map<std::string, PlyMesh> meshes_;  // by the path as resolved
};

// readPly, through the cache in use when there is one.
PlyMesh readPlyCached(const std::string& path);

}  // namespace ps
