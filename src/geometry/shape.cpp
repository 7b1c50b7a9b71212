#include "geometry/shape.h"

#include "math/warp.h"

namespace ps {

namespace {
// Embree calls this for each candidate hit before accepting it; clearing valid rejects it and
// traversal goes on. The ray is in the geometry's space (an instance's, inside instances) and
// its tfar is the candidate's distance.
void hitFilter(const RTCFilterFunctionNArguments* args) {
    auto* shape = static_cast<const Shape*>(args->geometryUserPtr);
    const unsigned n = args->N;
    for (unsigned i = 0; i < n; ++i) {
        if (args->valid[i] != -1) continue;
        Ray r{{RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i), RTCRayN_org_z(args->ray, n, i)},
              {RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i), RTCRayN_dir_z(args->ray, n, i)}};
        float t = RTCRayN_tfar(args->ray, n, i);
        if (!shape->acceptsHit(r, t, int(RTCHitN_primID(args->hit, n, i)), RTCHitN_u(args->hit, n, i),
                             RTCHitN_v(args->hit, n, i)))
            args->valid[i] = 0;
    }
}
}  // namespace

void Shape::installAlphaFilter(RTCGeometry g) const {
    if (alpha) installHitFilter(g);
}

void Shape::installHitFilter(RTCGeometry g) const {
    rtcSetGeometryUserData(g, const_cast<Shape*>(this));
    rtcSetGeometryIntersectFilterFunction(g, hitFilter);
    rtcSetGeometryOccludedFilterFunction(g, hitFilter);
}

std::optional<ShapeSample> Shape::sampleToward(int prim, Vec3 ref, Vec2 u) const {
    ShapeSample s = sampleArea(prim, u);
    s.pdfArea = s.pdf;
    Vec3 d = s.p - ref;
    float dist2 = lengthSquared(d);
    if (!(dist2 > 0)) return std::nullopt;
    float dist = std::sqrt(dist2);
    s.wi = d / dist;
    s.pdf = areaToSolidAngle(s.pdf, dist2, absDot(s.n, s.wi));
    if (!(s.pdf > 0) || !std::isfinite(s.pdf)) return std::nullopt;
    return s;
}

bool Shape::keepsHit(const Ray& r, float t, int embreePrim, float u, float v) const {
    if (!alpha) return true;
    SurfaceInteraction si;
    interaction(r, t, embreePrim, u, v, si);
    si.t = t;
    if (!areaLights.empty()) return alpha->keepsPoint(si.p, si.ng, si.uv);
    return alpha->keepsRayHit(si, r.o, r.d);
}

float Shape::pdfToward(int prim, Vec3 ref, Vec3 hitP, Vec3 hitN) const {
    Vec3 d = hitP - ref;
    float dist2 = lengthSquared(d);
    if (!(dist2 > 0)) return 0;
    float pdf = areaToSolidAngle(1.0f / area(prim), dist2, absDot(hitN, d) / std::sqrt(dist2));
    return std::isfinite(pdf) ? pdf : 0.0f;
}

}  // namespace ps
