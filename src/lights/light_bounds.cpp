#include "lights/light_bounds.h"

#include <algorithm>
#include <cmath>

namespace ps {

LightBounds unite(const LightBounds& a, const LightBounds& b) {
    if (a.phi == 0) return b;
    if (b.phi == 0) return a;
    DirectionCone cone = unite(DirectionCone(a.w, a.cosTheta_o), DirectionCone(b.w, b.cosTheta_o));
    // The widest emission of the two (cosines fall as angles grow).
    return LightBounds(unite(a.bounds, b.bounds), cone.w, a.phi + b.phi, cone.cosTheta,
                       std::min(a.cosTheta_e, b.cosTheta_e), a.twoSided || b.twoSided);
}

LightImportance::LightImportance(const LightBounds& b)
    : centre_(b.bounds.centroid()), radius_(length(b.bounds.hi - b.bounds.centroid())), w_(b.w), phi_(b.phi),
      // pbrt-v4's clamp of the falloff near the emitters (it compares the squared distance with
      // half the diagonal's length, not its square; kept, so that we choose as pbrt-v4 does),
      // and a floor where p is a point light's own position.
      invFalloffFloor_(1 / std::max(length(b.bounds.diagonal()) / 2, 1e-20f)), cosTheta_o_(b.cosTheta_o),
      sinTheta_o_(safeSqrt(1 - sqr(b.cosTheta_o))), cosTheta_e_(b.cosTheta_e), twoSided_(b.twoSided),
      allDirections_(b.cosTheta_o <= -1) {}

}  // namespace ps
