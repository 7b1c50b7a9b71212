// Which light paths an estimator cannot sample in a scene (thesis §10.2: each sampling
// technique covers only the paths whose vertices it can generate; a path with a specular
// vertex next to the eye, or a delta light seen through a specular surface, lies outside
// some techniques altogether). Such an integrator renders those paths black: an image darker
// than the others, not a noisier one. Users are warned, and `pathspace verify` and the
// agreement matrix leave the integrator out of that scene's comparisons.
#pragma once
#include <string>

#include "render/scene.h"

namespace ps {

// Why `integrator` cannot render all of the scene's light, or "" when it can. For a known
// name: createIntegrator reports an unknown one.
std::string missingPaths(const Scene& scene, const std::string& integrator);

// Why `integrator` would render some of the scene's surfaces other than the path tracer does,
// or "" when it would not: flat and cylinder curves turn to face each ray, so a light path
// meets a fibre other than a camera ray does, which only the hair BSDF's adjoint allows for
// (hair_bxdf.cpp); with any other material only path tracing is consistent there, as in
// pbrt-v4.
std::string inconsistentSurfaces(const Scene& scene, const std::string& integrator);

// Why `integrator` cannot render the scene's participating media, or "" when it can: the path
// tracer (pbrt-v4's volpath), the integrators over the shared subpaths (light, bdpt, pssmlt,
// mmlt) and Veach's mlt (mlt/veach/path_space_media.cpp) have medium vertices; emissive media
// outside path tracing not yet (issue 36): those refuse the scene (createIntegrator) rather
// than render it without.
std::string unsupportedMedia(const Scene& scene, const std::string& integrator);

// Why "light" or "mlt" cannot render through a camera without importance (orthographic,
// spherical, realistic): a phrase that follows the integrator's name.
std::string lensRequirement(const std::string& integrator);

}  // namespace ps
