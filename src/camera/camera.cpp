#include "camera/camera.h"

#include "math/warp.h"

namespace ps {

Camera::Camera(const Params& p) : params_(p) {
    float aspect = float(p.xRes) / float(p.yRes);
    const float* w = p.screenWindow;
    if (w[0] == 0 && w[1] == 0 && w[2] == 0 && w[3] == 0) {
        if (aspect > 1) {
            sx0_ = -aspect; sx1_ = aspect; sy0_ = -1; sy1_ = 1;
        } else {
            sx0_ = -1; sx1_ = 1; sy0_ = -1 / aspect; sy1_ = 1 / aspect;
        }
    } else {
        sx0_ = w[0]; sx1_ = w[1]; sy0_ = w[2]; sy1_ = w[3];
    }
    tanHalfFov_ = std::tan(radians(p.fovDeg) / 2);
}

Ray Camera::generateRay(const CameraSample& s) const {
    // Raster -> screen: row 0 is the top, at ymax.
    float sx = sx0_ + s.pFilm.x / params_.xRes * (sx1_ - sx0_);
    float sy = sy1_ - s.pFilm.y / params_.yRes * (sy1_ - sy0_);
    Vec3 o, d;
    if (params_.projection == Projection::Perspective) {
        d = Vec3(sx * tanHalfFov_, sy * tanHalfFov_, 1);  // normalised once, in world space
        o = {0, 0, 0};
    } else {
        o = {sx, sy, 0};
        d = {0, 0, 1};
    }
    if (params_.lensRadius > 0) {
        Vec2 lens = sampleConcentricDisk(s.pLens) * params_.lensRadius;
        float ft = params_.focalDistance / d.z;
        Vec3 pFocus = o + d * ft;
        o = {o.x + lens.x, o.y + lens.y, 0};
        d = pFocus - o;
    }
    const Transform& T = params_.worldFromCamera;
    return Ray{T.point(o), normalize(T.vector(d))};
}

}  // namespace ps
