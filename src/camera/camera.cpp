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
    pose_ = makePose(p.worldFromCamera);
    filmArea_ = std::fabs((sx1_ - sx0_) * (sy1_ - sy0_)) * tanHalfFov_ * tanHalfFov_;
    invImportanceNorm_ = 1 / (filmArea_ * lensArea());
    // Screen x = pFocus.x / (zFocus tan(fov/2)), raster x = (screen x - sx0) / (sx1 - sx0) xRes;
    // likewise y, flipped (row 0 at the top).
    zFocus_ = p.lensRadius > 0 ? p.focalDistance : 1.0f;
    kx_ = float(p.xRes) / ((sx1_ - sx0_) * zFocus_ * tanHalfFov_);
    bx_ = -sx0_ / (sx1_ - sx0_) * float(p.xRes);
    ky_ = float(p.yRes) / ((sy1_ - sy0_) * zFocus_ * tanHalfFov_);
    by_ = sy1_ / (sy1_ - sy0_) * float(p.yRes);
}

Camera::Pose Camera::makePose(const Transform& worldFromCamera) const {
    return Pose{worldFromCamera, worldFromCamera.inverse(), normalize(worldFromCamera.vector({0, 0, 1})),
                worldFromCamera.point({0, 0, 0})};
}

const Camera::Pose& Camera::poseAt(float time, std::optional<Pose>& scratch) const {
    if (!isMoving()) return pose_;
    return scratch.emplace(makePose(params_.motion.interpolate(time)));
}

Vec3 Camera::forward(float time) const {
    std::optional<Pose> scratch;
    return poseAt(time, scratch).forward;
}

void Camera::setFilterMargin(Vec2 m) {
    margin_ = m;
    float xr = float(params_.xRes), yr = float(params_.yRes);
    filmArea_ = std::fabs((sx1_ - sx0_) * (sy1_ - sy0_)) * tanHalfFov_ * tanHalfFov_ * ((xr + 2 * m.x) / xr) *
                ((yr + 2 * m.y) / yr);
    invImportanceNorm_ = 1 / (filmArea_ * lensArea());
}

bool Camera::rasterOf(Vec3 oCam, Vec3 dCam, Vec2* pRaster) const {
    // Every ray through a lens point focused at film point x passes through x's pinhole image
    // on the plane of focus (z = 1 for a pinhole), so that point names the film position.
    // Only dCam's direction matters: it need not be normalised.
    float tf = (zFocus_ - oCam.z) / dCam.z;
    float rx = kx_ * (oCam.x + dCam.x * tf) + bx_;
    float ry = by_ - ky_ * (oCam.y + dCam.y * tf);
    if (pRaster) *pRaster = {rx, ry};
    return rx >= -margin_.x && rx < params_.xRes + margin_.x && ry >= -margin_.y && ry < params_.yRes + margin_.y;
}

float Camera::We(const Ray& r, Vec2* pRaster) const {
    if (!hasImportance()) return 0;
    std::optional<Pose> scratch;
    const Pose& pose = poseAt(r.time, scratch);
    return importance(pose, normalize(r.d), pose.cameraFromWorld.point(r.o), pRaster);
}

float Camera::importance(const Pose& pose, Vec3 d, Vec3 oCam, Vec2* pRaster) const {
    float cosT = dot(d, pose.forward);
    if (!(cosT > 0)) return 0;
    if (!rasterOf(oCam, pose.cameraFromWorld.vector(d), pRaster)) return 0;
    float cos2 = cosT * cosT;
    return invImportanceNorm_ / (cos2 * cos2);
}

void Camera::pdfWe(const Ray& r, float* pdfPos, float* pdfDir) const {
    *pdfPos = *pdfDir = 0;
    if (!hasImportance()) return;
    std::optional<Pose> scratch;
    const Pose& pose = poseAt(r.time, scratch);
    Vec3 d = normalize(r.d);
    float cosT = dot(d, pose.forward);
    if (!(cosT > 0)) return;
    if (!rasterOf(pose.cameraFromWorld.point(r.o), pose.cameraFromWorld.vector(d), nullptr)) return;
    *pdfPos = 1 / lensArea();
    *pdfDir = pdfDirAt(cosT);
}

float Camera::generatedRayPdfDir(const Ray& r) const {
    if (!hasImportance()) return 0;
    float cosT = dot(r.d, forward(r.time));
    return cosT > 0 ? pdfDirAt(cosT) : 0.0f;
}

std::optional<CameraWiSample> Camera::sampleWi(Vec3 ref, float time, Vec2 u) const {
    if (!hasImportance()) return std::nullopt;
    std::optional<Pose> scratch;
    const Pose& pose = poseAt(time, scratch);
    // A pinhole has one lens point (u is still consumed by the caller, keeping dimensions aligned).
    Vec2 lens = params_.lensRadius > 0 ? sampleConcentricDisk(u) * params_.lensRadius : Vec2(0, 0);
    CameraWiSample s;
    s.pLens = params_.lensRadius > 0 ? pose.worldFromCamera.point({lens.x, lens.y, 0}) : pose.lensCentre;
    s.nLens = pose.forward;
    Vec3 toLens = s.pLens - ref;
    float dist2 = lengthSquared(toLens);
    if (!(dist2 > 0)) return std::nullopt;
    s.wi = toLens / std::sqrt(dist2);
    float cosLens = std::fabs(dot(s.nLens, s.wi));
    if (!(cosLens > 0)) return std::nullopt;
    // Area density 1/lensArea on the lens, as a solid angle at ref (thesis eq. 8.10).
    s.pdf = dist2 / (cosLens * lensArea());
    s.We = importance(pose, -s.wi, {lens.x, lens.y, 0}, &s.pRaster);
    if (!(s.We > 0)) return std::nullopt;
    s.pdfDir = pdfDirAt(cosLens);  // as pdfWe gives it
    return s;
}

std::optional<LensCrossing> Camera::intersectLens(const Ray& r, float tMax) const {
    if (!hasLensDisk()) return std::nullopt;
    std::optional<Pose> scratch;
    const Pose& pose = poseAt(r.time, scratch);
    // The lens is the disk z = 0, radius lensRadius, in camera space; light reaches its front
    // travelling towards -z (affine maps keep the ray's parameter).
    const Vec3 o = pose.cameraFromWorld.point(r.o), d = pose.cameraFromWorld.vector(r.d);
    if (!(d.z < 0) || !(o.z > 0)) return std::nullopt;
    LensCrossing c;
    c.t = -o.z / d.z;
    if (!(c.t < tMax)) return std::nullopt;
    const Vec3 lens(o.x + c.t * d.x, o.y + c.t * d.y, 0);
    if (lens.x * lens.x + lens.y * lens.y > params_.lensRadius * params_.lensRadius) return std::nullopt;
    c.p = r.o + r.d * c.t;
    const Vec3 w = -normalize(r.d);
    c.We = importance(pose, w, lens, &c.pRaster);
    if (!(c.We > 0)) return std::nullopt;
    c.cosLens = dot(w, pose.forward);
    return c;
}

Ray Camera::generateRay(const CameraSample& s, float* weight) const {
    return generateRayAt(s, shutterTime(s.time), weight);
}

Ray Camera::generateRayAt(const CameraSample& s, float time, float* weight) const {
    Ray r = generateRay(s, isMoving() ? params_.motion.interpolate(time) : params_.worldFromCamera, weight);
    r.time = time;
    return r;
}

Ray Camera::generateRay(const CameraSample& s, const Transform& T, float* weight) const {
    if (weight) *weight = 1;
    if (params_.projection == Projection::Realistic) {
        Ray r{{0, 0, 0}, {0, 0, 1}};
        float w = params_.lens->generateRay(s.pFilm, s.pLens, &r);
        if (weight) *weight = w;
        return Ray{T.point(r.o), normalize(T.vector(r.d))};
    }
    if (params_.projection == Projection::Spherical) {
        Vec2 uv(s.pFilm.x / params_.xRes, s.pFilm.y / params_.yRes);
        return Ray{T.point({0, 0, 0}), normalize(T.vector(sphericalCameraDirection(params_.mapping, uv)))};
    }
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
    return Ray{T.point(o), normalize(T.vector(d))};
}

}  // namespace ps
