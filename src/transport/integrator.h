// An integrator estimates the radiance arriving along a camera ray.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include "geometry/ray.h"
#include "math/spectrum.h"
#include "mc/sampler.h"
#include "render/scene.h"
#include "util/scratch.h"

namespace ps {

// Per-thread counters, summed at the end of a render.
struct PathStats {
    uint64_t cameraPaths = 0;
    uint64_t rays = 0;        // closest-hit rays, camera rays included
    uint64_t shadowRays = 0;  // visibility tests
    uint64_t guarded = 0;     // non-finite values caught at their source
    PathStats& operator+=(const PathStats& o) {
        cameraPaths += o.cameraPaths; rays += o.rays; shadowRays += o.shadowRays; guarded += o.guarded;
        return *this;
    }
};

class Integrator {
public:
    virtual ~Integrator() = default;
    virtual Spectrum Li(const Ray& ray, Sampler& sampler, ScratchBuffer& scratch, PathStats& stats) const = 0;
};

// Names: "path". Throws InputError for an unknown name.
std::unique_ptr<Integrator> createIntegrator(const std::string& name, const Scene& scene);

}  // namespace ps
