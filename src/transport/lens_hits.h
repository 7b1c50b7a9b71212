// Light subpath rays that cross a thin lens by themselves: the t = 0 strategy (thesis §10.2,
// Veach's t = 0 paths). The scene's intersector does not know the lens, so each light-walk
// segment is tested against the aperture disk explicitly (Camera::intersectLens); the segment
// ends at its first scene hit, which handles occlusion. A lens is a surface of area
// pi r^2: a light path reaches it with a positive density, where a pinhole is never hit.
// In a medium the segment's free flight must also pass the lens before it collides
// (subpaths_media.cpp).
#pragma once
#include <optional>

#include "camera/camera.h"
#include "math/spectrum.h"

namespace ps {

// One crossing: the path of the light subpath's vertices 0 .. index - 1 and the lens as
// vertex `index` (strategy s = index + 1, t = 0).
struct LensHit {
    int index = 0;
    LensCrossing lens;
    // The walk's throughput arriving at the lens; in a scene with media also divided by the
    // channel mean of its flights' density ratios (spectral MIS, subpaths_media.cpp), so that
    // beta W_e is the strategy's estimate in every scene.
    Spectrum beta;
    float pdfDir = 0;  // solid-angle density of the direction sampled at vertex index - 1
};

// Where a walk records its crossings: room for `capacity` (one per segment suffices).
struct LensHits {
    LensHit* hits = nullptr;
    int n = 0, capacity = 0;
};

// Where the segment of `ray` up to tMax (leaving light subpath vertex index - 1) crosses the
// lens, if the walk records a crossing there. Only from a scattering vertex (index >= 2): a
// light seen directly through the lens is the camera subpath's (s = 0) alone, as path
// tracing sees it.
inline std::optional<LensCrossing> lensCrossing(const Camera& camera, const Ray& ray, float tMax, int index,
                                                const LensHits& out) {
    if (index < 2 || out.n >= out.capacity) return std::nullopt;
    return camera.intersectLens(ray, tMax);
}

inline void recordLensHit(const LensCrossing& c, int index, const Spectrum& beta, float pdfDir, LensHits& out) {
    out.hits[out.n++] = LensHit{index, c, beta, pdfDir};
}

// Both of the above, for a segment in a vacuum.
inline void recordLensCrossing(const Camera& camera, const Ray& ray, float tMax, int index, const Spectrum& beta,
                               float pdfDir, LensHits& out) {
    if (const auto c = lensCrossing(camera, ray, tMax, index, out)) recordLensHit(*c, index, beta, pdfDir, out);
}

}  // namespace ps
