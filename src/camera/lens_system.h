// The realistic camera's lens system (pbrt-v4's semantics): rays from the film traced through
// spherical interfaces and the aperture stop, the film placed for the focus distance by the
// thick-lens approximation, and exit-pupil bounds per film radius from which the rear
// element is sampled.
//
// Camera space: the film is the plane z = 0, the rear element's vertex at z = rearZ(), the
// front element's at frontZ(), the scene beyond (+z). Film points are mirrored through the
// optical axis (the lens inverts the image), so raster row 0 (the top) lies at -y.
#pragma once
#include <memory>
#include <optional>
#include <vector>
#include "camera/aperture_mask.h"
#include "camera/lens_file.h"
#include "geometry/ray.h"

namespace ps {

struct PupilBounds {
    Vec2 lo{1e30f, 1e30f}, hi{-1e30f, -1e30f};
    bool empty() const { return lo.x > hi.x || lo.y > hi.y; }
    bool contains(Vec2 p) const { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }
    float area() const { return empty() ? 0.0f : (hi.x - lo.x) * (hi.y - lo.y); }
};

class LensSystem {
public:
    struct Params {
        std::vector<LensInterface> interfaces;  // scene side first
        float apertureDiameter = 1e-3f;  // metres; replaces the stop's diameter unless larger
        float focusDistance = 10;        // from the film plane to the plane in focus
        float filmDiagonal = 0.035f;     // metres
        int xRes = 1280, yRes = 720;     // the full film resolution
        std::shared_ptr<const ApertureMask> mask;  // none: the circular stop
        int pupilSamplesPerSegment = 1 << 20;      // rear-element points tried per film segment
    };
    // Throws InputError (without a location: the caller adds the directive's) when the
    // thick-lens approximation cannot be traced or the focus distance is too short.
    explicit LensSystem(Params p);

    // Traces a camera-space ray from the film side out of the front element; returns the
    // transmission (the aperture mask's value, 1 for a circular stop) or 0 if the ray is
    // blocked (an aperture, a missed element, total internal reflection).
    float traceFromFilm(const Ray& rFilm, Ray* out) const;
    // The reverse: a camera-space ray from the scene side to behind the rear element.
    // Apertures are circular here (the aperture mask is ignored), as for focusing.
    bool traceFromScene(const Ray& rScene, Ray* out) const;

    // A camera-space ray for raster point pFilm and lens sample u in [0,1)^2: returns its
    // weight (transmission times cos^4(theta) / (pdf of the rear point * rearZ^2), theta
    // the angle of the film-to-rear-element segment to the axis), 0 when the ray is
    // blocked or the film point sees no exit pupil (then *out is untouched).
    float generateRay(Vec2 pFilm, Vec2 u, Ray* out) const;

    // True when apertureDiameter exceeded the stop's own diameter and was clamped to it.
    bool apertureClamped() const { return apertureClamped_; }
    float rearZ() const { return interfaces_.back().thickness; }  // the film distance
    float frontZ() const;
    const std::vector<LensInterface>& interfaces() const { return interfaces_; }
    const std::vector<PupilBounds>& exitPupilBounds() const { return pupil_; }
    // Camera-space position of the film point for a raster point.
    Vec3 filmPoint(Vec2 pRaster) const;
    // Thick-lens cardinal points, computed before focusing: z (lens space, i.e. the negated
    // camera-space z with the film at the rear thickness of the description) of the
    // principal planes and focal points, [0] on the film side and [1] on the scene side.
    struct Cardinal {
        float principal[2], focal[2];
    };
    const Cardinal& cardinalPoints() const { return cardinal_; }

private:
    Cardinal thickLens() const;
    float focusedRearThickness(float focusDistance) const;
    PupilBounds boundExitPupil(float r0, float r1, const std::vector<Vec2>& halton) const;
    float rearRadius() const { return interfaces_.back().apertureRadius; }

    std::vector<LensInterface> interfaces_;
    std::shared_ptr<const ApertureMask> mask_;
    float filmDiagonal_ = 0.035f;
    Vec2 filmSize_;  // physical width and height of the film
    int xRes_ = 1, yRes_ = 1;
    Cardinal cardinal_{};
    std::vector<PupilBounds> pupil_;
    bool apertureClamped_ = false;  // per film-radius segment from the centre to a corner
};

}  // namespace ps
