// Which light paths an estimator cannot sample in a scene (thesis §10.2: each sampling
// technique covers only the paths whose vertices it can generate; a path with a specular
// vertex next to the eye, or a delta light seen through a specular surface, lies outside
// some techniques altogether). Such an integrator renders those paths black: an image darker
// than the others, not a noisier one. Users are warned, and `pathspace verify` and the
// agreement matrix leave the integrator out of that scene's comparisons.
#pragma once
#include <string>
#include <vector>

#include "render/scene.h"

namespace ps {

// One class of light paths that no technique of an integrator samples in a scene (thesis
// §1.1: a delta light seen through specular vertices by a pinhole is such a class for every
// unbiased technique; §10.2: each of BDPT's strategies covers only the paths whose vertices it
// can generate). Detected from the scene's lights, materials and camera at load time.
struct UnsampledPaths {
    // "delta-specular-eye": L S+ E from a delta light, through a delta camera; "delta-caustic":
    // path tracing's L S+ D ... E from a delta light; "light-*": light tracing's own (its lens,
    // the environment, a camera in a medium, specular surfaces seen by the camera);
    // "mlt-lens": Veach's mlt through a camera without importance; "medium-emission": light
    // and mlt with emissive media.
    std::string id;
    // What is missed, naming the lights, the materials and the camera, and Veach's remedies.
    std::string message;
    // No integrator samples the class with this scene: all render it black alike, so
    // comparisons between integrators stay fair (missingPaths leaves such classes out).
    bool everyIntegrator = false;
};

// Every class `integrator` misses in the scene, once each, in a fixed order (for the warnings
// at scene load and --stats). For a known name.
std::vector<UnsampledPaths> unsampledPaths(const Scene& scene, const std::string& integrator);

// Whether `integrator` has the t = 0 strategy in this scene (a light subpath reaching the lens
// by itself, thesis §10.2): BDPT, light tracing and pssmlt through a thin lens (lensradius > 0),
// with or without participating media.
bool samplesLensHits(const Scene& scene, const std::string& integrator);

// Why `integrator` cannot render all of the scene's light that another integrator renders, or
// "" when it can: the first of unsampledPaths that not every integrator misses. For a known
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
// mmlt) and Veach's mlt (mlt/veach/path_space_media.cpp) have medium vertices. Emission
// inside media: path, bdpt, pssmlt and mmlt sample it by the camera walk's free flights;
// light and mlt have no strategy for it ("medium-emission" of unsampledPaths) and refuse
// the scene (createIntegrator) rather than render it without.
std::string unsupportedMedia(const Scene& scene, const std::string& integrator);

// Why "light" or "mlt" cannot render through a camera without importance (orthographic,
// spherical, realistic): a phrase that follows the integrator's name.
std::string lensRequirement(const std::string& integrator);

}  // namespace ps
