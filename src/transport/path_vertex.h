// Path vertices in the area-measure formulation of the path integral (thesis ch. 8):
// each vertex of a camera or light subpath keeps its throughput and the densities, in area
// measure at this vertex, with which the forward walk and the reverse (adjoint) walk would
// generate it. Shared by light tracing and bidirectional path tracing (thesis ch. 10).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <new>
#include "geometry/interaction.h"
#include "lights/light.h"
#include "materials/bxdf.h"
#include "math/frame.h"
#include "math/spectrum.h"
#include "media/medium.h"

namespace ps {

// Medium: a scattering point in a participating medium, whose "BSDF" is the phase function
// and whose densities are per unit volume (no cosine: thesis ch. 8's area measure becomes
// the volume measure there, as in pbrt-v4's BDPT).
enum class VertexKind : uint8_t { Camera, Light, Surface, Medium };

struct PathVertex {
    VertexKind kind = VertexKind::Surface;
    TransportMode mode = TransportMode::Radiance;  // which subpath built it
    bool delta = false;     // scattered by a specular lobe, a delta light's position, or a camera no connection reaches
    bool infinite = false;  // at infinity: a light vertex of an infinite or distant light,
                            // or where a camera ray escaped
    bool nonSpecular = false;  // surfaces: the BxDF has a diffuse or glossy lobe
    bool flatShading = false;  // surfaces: the adjoint shading factor is 1 (ns == ng, or facesRay: subpaths.cpp)
    bool dispersive = false;   // surfaces (spectral mode): the BxDF follows lambda[0] alone
    bool facesRay = false;     // on a flat curve (geometry/fibre_kind.h): see densityCos
    Spectrum beta;          // throughput of the subpath up to and including this vertex
    Vec3 p;
    Vec3 ng, ns;            // zero for points without a surface (pinhole, point lights)
    Vec3 wo;                // unit direction towards the previous vertex of its subpath
    Vec3 woLocal;           // wo in the shading frame (surfaces)
    Vec2 uv;
    Frame frame;            // shading frame (surfaces)
    const BxDF* bxdf = nullptr;    // surfaces
    const Light* light = nullptr;  // the emitter at a light vertex or an emissive surface
    float pdfFwd = 0;       // density of this vertex from its subpath's walk
    float pdfRev = 0;       // density of this vertex from the opposite walk
    float toPrevArea = 0;   // areaFactor(*this, previous vertex of its subpath), surfaces
    float time = 0;         // the path's scene time (motion blur), for the rays it connects
    // Scenes with media only (subpaths_media.cpp): the medium on the side of ng and the other
    // (both the same for medium vertices and points without a surface), and the ratios of each
    // channel's density of the walk's free flights up to here to the hero channel's (the
    // spectral MIS of media/delta_tracking.h; 1 elsewhere and unread without media).
    const Medium* mediumAbove = nullptr;
    const Medium* mediumBelow = nullptr;
    Spectrum rU{1.0f};
    // Camera subpaths in emissive media: the light the media emit along the free flights that
    // leave this vertex (pbrt-v4's sigma_a Le at tentative collisions, weighted and divided by
    // the path's channel-mean density already). A point that emits inside a medium is the last
    // vertex of strategy (s = 0, t = this vertex's index + 2), which no other strategy
    // samples (no light sampler chooses points in volumes): its MIS weight is 1.
    Spectrum mediumLe;

    bool onSurface() const { return ng.x != 0 || ng.y != 0 || ng.z != 0; }
    // An escaped camera ray, or an emitter found by the camera subpath, or a light vertex.
    bool isLight() const { return kind == VertexKind::Light || (kind == VertexKind::Surface && light); }
    bool isDeltaLight() const { return kind == VertexKind::Light && light && light->isDelta(); }
    bool isInfiniteLight() const { return kind == VertexKind::Light && infinite; }
    const Medium* mediumToward(Vec3 w) const { return dot(w, ng) < 0 ? mediumBelow : mediumAbove; }
    // Whether a deterministic connection to another vertex can be made here.
    bool connectible() const {
        switch (kind) {
            case VertexKind::Camera: return true;
            case VertexKind::Light: return !light || light->type() != LightType::DeltaDirection;
            case VertexKind::Surface: return bxdf && nonSpecular;
            case VertexKind::Medium: return true;
        }
        return false;
    }
};

// A fresh vertex in place. Assigning PathVertex{} builds a temporary and copies it with wide
// stores that the field writes after it then stall on (store forwarding), a few percent of BDPT.
inline PathVertex& resetVertex(PathVertex& v) { return *new (&v) PathVertex(); }

// The cosine that turns a solid-angle density of a direction w arriving at v into an area
// density there. A flat curve faces each ray, so the point a path meets has no normal of its
// own: every technique's density is per unit of the fibre's area (its width times length),
// which a ray along w crosses with the fibre's projected width, sqrt(1 - (w . axis)^2), not
// with the cosine of a ribbon that faced some other ray. The shading frame's s is the axis.
inline float densityCos(const PathVertex& v, Vec3 w) {
    if (v.facesRay) {
        const float a = dot(v.frame.s, w);
        return std::sqrt(std::max(0.0f, 1 - a * a));
    }
    return std::fabs(dot(v.ng, w));
}

// The factor |cos theta_to| / d^2 that turns a solid-angle density at `from` of choosing the
// direction to `to` into an area density at `to` (thesis eq. 8.10); 1 for vertices at
// infinity, which keep solid-angle densities.
inline float areaFactor(const PathVertex& from, const PathVertex& to) {
    if (to.isInfiniteLight()) return 1;
    Vec3 w = to.p - from.p;
    float d2 = lengthSquared(w);
    if (!(d2 > 0)) return 0;
    float invDist2 = 1 / d2;
    return to.onSurface() ? densityCos(to, w * std::sqrt(invDist2)) * invDist2 : invDist2;
}
// areaFactor(a, b) and areaFactor(b, a) from one distance (a walk needs both at each vertex).
inline void areaFactors(const PathVertex& a, const PathVertex& b, float* aToB, float* bToA) {
    if (a.isInfiniteLight() || b.isInfiniteLight()) {
        *aToB = areaFactor(a, b);
        *bToA = areaFactor(b, a);
        return;
    }
    Vec3 w = b.p - a.p;
    float d2 = lengthSquared(w);
    if (!(d2 > 0)) {
        *aToB = *bToA = 0;
        return;
    }
    float invDist2 = 1 / d2;
    Vec3 wn = w * std::sqrt(invDist2);
    *aToB = b.onSurface() ? densityCos(b, wn) * invDist2 : invDist2;
    *bToA = a.onSurface() ? densityCos(a, wn) * invDist2 : invDist2;
}
inline float solidAngleToArea(const PathVertex& from, float pdf, const PathVertex& to) {
    return pdf * areaFactor(from, to);
}

}  // namespace ps
