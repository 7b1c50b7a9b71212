// Projective cameras with pbrt-v4's conventions (PBRT-CONVENTIONS §1): raster y points
// down, fov spans the shorter image axis, focus on the plane z = focaldistance.
#pragma once
#include "geometry/ray.h"
#include "math/transform.h"

namespace ps {

struct CameraSample {
    Vec2 pFilm;  // raster position (pixels, continuous)
    Vec2 pLens;  // [0,1)^2
};

class Camera {
public:
    enum class Projection { Perspective, Orthographic };
    struct Params {
        Projection projection = Projection::Perspective;
        Transform worldFromCamera;
        int xRes = 1280, yRes = 720;
        float fovDeg = 90;
        float screenWindow[4] = {0, 0, 0, 0};  // xmin xmax ymin ymax; all zero = default
        float lensRadius = 0, focalDistance = 1e6f;
    };
    explicit Camera(const Params& p);

    // A world-space ray through the film point; the weight is 1 for these cameras.
    Ray generateRay(const CameraSample& s) const;
    Vec3 position() const { return params_.worldFromCamera.point({0, 0, 0}); }
    const Params& params() const { return params_; }

private:
    Params params_;
    float sx0_, sx1_, sy0_, sy1_;  // screen window
    float tanHalfFov_ = 1;
};

}  // namespace ps
