#include "render/camera_medium_check.h"

#include "geometry/interaction.h"
#include "geometry/ray.h"
#include "render/scene.h"

namespace ps {

std::optional<const Medium*> mediumImpliedAt(const Scene& scene, Vec3 p) {
    std::optional<const Medium*> implied;
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z) {
                if (x == 0 && y == 0 && z == 0) continue;
                // Slightly off the axes and diagonals: a probe along an edge of an axis-aligned
                // box would meet two faces at once.
                const Vec3 d = normalize(Vec3(x + 0.0123f, y + 0.0171f * x, z - 0.0097f * y));
                Ray ray{p, d};
                // Surfaces that do not change medium leave it as it is: go on past them.
                for (int hop = 0; hop < 64; ++hop) {
                    SurfaceInteraction si;
                    if (!scene.intersect(ray, si)) break;
                    if (si.mediumTransition) {
                        const Medium* here = si.mediumToward(-d, nullptr);  // the side the probe came from
                        if (implied && *implied != here) return std::nullopt;
                        implied = here;
                        break;
                    }
                    ray = spawnRay(si.p, si.ng, d, 0);
                }
            }
    return implied;
}

}  // namespace ps
