// What kind of fibre a curve hit lies on. Its light transport depends on it: flat and
// cylinder curves are strips turned to face each ray, so the surface a path meets depends on
// the ray that met it. The hair BSDF and the path-space densities read it.
#pragma once
#include <cstdint>

namespace ps {

enum class FibreKind : int8_t {
    None,       // not a curve, or a ribbon with fixed normals (an ordinary surface)
    FacingRay,  // flat or cylinder curve
};

}  // namespace ps
