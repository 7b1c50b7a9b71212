// Projective cameras with pbrt-v4's conventions (PBRT-CONVENTIONS §1): raster y points
// down, fov spans the shorter image axis, focus on the plane z = focaldistance. Also the
// spherical camera (a pinhole seeing every direction; see spherical_mapping.h) and the
// realistic camera (rays traced through a lens system; see lens_system.h).
#pragma once
#include <memory>
#include <optional>
#include "camera/lens_system.h"
#include "camera/spherical_mapping.h"
#include "geometry/ray.h"
#include "math/animated_transform.h"
#include "math/transform.h"

namespace ps {

struct CameraSample {
    Vec2 pFilm;  // raster position (pixels, continuous)
    Vec2 pLens;  // [0,1)^2
    float time = 0;  // [0,1): where in the shutter interval the ray travels
};

// A camera connection from a scene point (the t = 1 strategies, thesis §10.2).
struct CameraWiSample {
    float We = 0;     // importance arriving at the lens point from the reference point
    Vec3 wi;          // unit direction from the reference point towards the lens
    float pdf = 0;    // solid angle at the reference point
    Vec3 pLens;       // world-space point on the lens
    Vec3 nLens;       // lens normal (the viewing direction)
    Vec2 pRaster;     // where the contribution lands on the film
    float pdfDir = 0; // the camera's own density (solid angle) of emitting along -wi
};

// Where a light subpath's ray crosses the lens (the t = 0 strategy, thesis §10.2).
struct LensCrossing {
    float t = 0;      // the ray's parameter at the lens
    Vec3 p;           // world-space point on the lens
    float We = 0;     // importance leaving p back along the ray (towards where it came from)
    Vec2 pRaster;     // where the contribution lands on the film
    float cosLens = 0;  // |cos| between the ray and the lens normal
};

class Camera {
public:
    enum class Projection { Perspective, Orthographic, Spherical, Realistic };
    struct Params {
        Projection projection = Projection::Perspective;
        Transform worldFromCamera;
        // A moving camera (ActiveTransform around Camera): its world-from-camera keyframes.
        // Not animated: worldFromCamera holds at every time.
        AnimatedTransform motion;
        float shutterOpen = 0, shutterClose = 1;
        int xRes = 1280, yRes = 720;
        float fovDeg = 90;
        float screenWindow[4] = {0, 0, 0, 0};  // xmin xmax ymin ymax; all zero = default
        float lensRadius = 0, focalDistance = 1e6f;  // projective cameras only
        SphericalMapping mapping = SphericalMapping::EqualArea;  // spherical only
        std::shared_ptr<const LensSystem> lens;                  // realistic only
    };
    explicit Camera(const Params& p);

    // A world-space ray through the film point. Its time is pbrt-v4's: the shutter interval at
    // s.time, and a moving camera sits where it is then. *weight (if given) receives the
    // ray's weight: 1, except for the realistic camera, whose rays carry the lens system's
    // weight and 0 when the lens blocks them (then the ray is meaningless).
    Ray generateRay(const CameraSample& s, float* weight = nullptr) const;
    // generateRay at a given scene time instead of s.time's point of the shutter (a path
    // whose time is already chosen: Veach's mutations keep it).
    Ray generateRayAt(const CameraSample& s, float time, float* weight = nullptr) const;
    // The scene time at fraction u in [0, 1) of the shutter interval.
    float shutterTime(float u) const { return (1 - u) * params_.shutterOpen + u * params_.shutterClose; }
    bool isMoving() const { return params_.motion.isAnimated(); }
    // Whether generateRay reads CameraSample::pLens.
    bool usesLensSample() const { return params_.lensRadius > 0 || params_.projection == Projection::Realistic; }
    Vec3 position() const { return params_.worldFromCamera.point({0, 0, 0}); }
    const Params& params() const { return params_; }

    // Importance (thesis §8.1.1 / pbrt-v4's PerspectiveCamera): W_e = 1 / (A lensArea cos^4)
    // over the film area A at unit distance, so that it integrates to one over the whole
    // film; zero outside it. Only perspective cameras have a non-delta importance (none is
    // implemented for the spherical camera, so light paths cannot reach its film).
    // Each of the following places a moving camera where it is at a scene time (the ray's
    // r.time, or `time`): a path has one time, and its connections to the lens, their
    // importance, densities and film positions all use the lens at that time.
    bool hasImportance() const { return params_.projection == Projection::Perspective; }
    // W_e for the world-space ray leaving the lens; *pRaster receives the film point.
    float We(const Ray& r, Vec2* pRaster = nullptr) const;
    // Densities of generateRay choosing r: position on the lens (area) and direction.
    void pdfWe(const Ray& r, float* pdfPos, float* pdfDir) const;
    // pdfWe's directional density for a ray this camera generated itself: on the film by
    // construction, so without the raster test (once per camera subpath). r as generateRay
    // returned it: its direction already unit length.
    float generatedRayPdfDir(const Ray& r) const;
    // Samples a lens point seen from ref at scene time `time` and the importance it sends there.
    std::optional<CameraWiSample> sampleWi(Vec3 ref, float time, Vec2 u) const;
    // A thin lens (perspective with lensradius > 0): a disk that light subpaths can hit.
    bool hasLensDisk() const { return hasImportance() && params_.lensRadius > 0; }
    // Area density of generateRay's lens point (uniform over the disk; a pinhole has none).
    float lensPdfArea() const { return 1 / lensArea(); }
    // The crossing of ray r (from the scene towards the lens front, before tMax) with the lens
    // disk at r.time, where the importance sent back along it is not zero; thin lens only.
    std::optional<LensCrossing> intersectLens(const Ray& r, float tMax) const;
    // The viewing direction in world space (the lens normal) at scene time `time`.
    Vec3 forward(float time) const;
    // The pixel filter's radius: camera samples (and light paths splatted onto the film)
    // reach that far beyond the film's edge, so importance extends over the film widened by
    // it on every side; splats are normalised by the widened film's pixel count to match.
    void setFilterMargin(Vec2 rasterMargin);

private:
    // The camera placed at one scene time.
    struct Pose {
        Transform worldFromCamera, cameraFromWorld;
        Vec3 forward;     // the viewing direction, unit
        Vec3 lensCentre;  // world position of the pinhole / lens centre
    };
    Pose makePose(const Transform& worldFromCamera) const;
    // The pose at scene time `time`: the fixed one, or `scratch` made by interpolating the
    // keyframes (left empty for a fixed camera, which costs nothing).
    const Pose& poseAt(float time, std::optional<Pose>& scratch) const;
    // generateRay with world-from-camera T (the transform at the ray's time).
    Ray generateRay(const CameraSample& s, const Transform& T, float* weight) const;
    float lensArea() const { return params_.lensRadius > 0 ? kPi * params_.lensRadius * params_.lensRadius : 1.0f; }
    // Film point for a camera-space direction from camera-space lens point o; false off the film.
    bool rasterOf(Vec3 oCam, Vec3 dCam, Vec2* pRaster) const;
    // We for the unit world direction d leaving camera-space lens point oCam, camera at pose.
    float importance(const Pose& pose, Vec3 d, Vec3 oCam, Vec2* pRaster) const;
    // pdfWe's directional density for a direction at cosT to the viewing direction: uniform
    // over the film area at z = 1, converted to solid angle.
    float pdfDirAt(float cosT) const { return 1 / (filmArea_ * cosT * cosT * cosT); }

    Params params_;
    Pose pose_;           // at every time for a camera that does not move
    float filmArea_ = 1;  // screen window area at z = 1, widened by the filter margin
    Vec2 margin_;         // filter radius in raster units
    float sx0_, sx1_, sy0_, sy1_;  // screen window
    float tanHalfFov_ = 1;
    // rasterOf's map from the plane of focus to raster: rx = kx * x + bx, ry = by - ky * y.
    float kx_ = 1, bx_ = 0, ky_ = 1, by_ = 0;
    float zFocus_ = 1;
    float invImportanceNorm_ = 1;  // 1 / (film area * lens area), for We
};

}  // namespace ps
