#include "geometry/shape.h"

#include "math/warp.h"

namespace ps {

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

float Shape::pdfToward(int prim, Vec3 ref, Vec3 hitP, Vec3 hitN) const {
    Vec3 d = hitP - ref;
    float dist2 = lengthSquared(d);
    if (!(dist2 > 0)) return 0;
    float pdf = areaToSolidAngle(1.0f / area(prim), dist2, absDot(hitN, d) / std::sqrt(dist2));
    return std::isfinite(pdf) ? pdf : 0.0f;
}

}  // namespace ps
