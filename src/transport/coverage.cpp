#include "transport/coverage.h"

#include <cstdio>
#include <optional>
#include <set>
#include <vector>

#include "geometry/curve.h"
#include "materials/bxdf.h"
#include "materials/hair_material.h"
#include "transport/mlt/veach/mutator.h"
#include "util/error.h"

namespace ps {

namespace {

// Whether a material may scatter through a delta lobe: a mirror, smooth glass, or a smooth
// coating over anything. Judged from the BxDF at one point (a textured roughness is assumed
// the same everywhere; a mix by the member it resolves to there).
bool mayScatterSpecularly(const Material& m) {
    MaterialEvalContext ctx;
    ctx.p = Vec3(0, 0, 0);
    ctx.n = Vec3(0, 0, 1);
    ctx.uv = Vec2(0.5f, 0.5f);
    ctx.wo = Vec3(0, 0, 1);
    ctx.dpdu = Vec3(1, 0, 0);
    const Material* resolved = m.resolve(ctx);
    if (!resolved) return false;
    ScratchBuffer scratch(4096);
    const BxDF* b = resolved->constantBxDF();
    if (!b) b = resolved->bxdf(ctx, scratch);
    if (!b) return false;
    return (b->flags() & kSpecular) || b->coatingMirrorReflectance(Vec3(0, 0, 1)) > 0 || b->specularThroughCoating();
}

// The scene's lights and materials that make classes of paths unsampled: delta lights (point,
// spot, goniometric, projection, distant), lights at infinity, and materials that may scatter
// through a delta lobe; each once, in scene order.
struct SceneTraits {
    std::vector<const Light*> delta, infinite;
    std::vector<const Material*> specular;
};

SceneTraits traitsOf(const Scene& scene) {
    SceneTraits t;
    std::set<const Material*> seen;
    for (const Shape* shape : scene.shapes())
        if (shape->material && seen.insert(shape->material).second && mayScatterSpecularly(*shape->material))
            t.specular.push_back(shape->material);
    for (const auto& light : scene.lights()) {
        if (light->isDelta()) t.delta.push_back(light.get());
        if (light->type() == LightType::Infinite) t.infinite.push_back(light.get());
    }
    return t;
}

// At most three names, then how many more.
std::string listed(const std::vector<std::string>& names) {
    std::string out;
    for (size_t i = 0; i < names.size() && i < 3; ++i) out += (i ? "; " : "") + names[i];
    if (names.size() > 3) out += "; and " + std::to_string(names.size() - 3) + " more";
    return out;
}

std::string lightNames(const std::vector<const Light*>& lights) {
    std::vector<std::string> names;
    for (const Light* l : lights) {
        if (!l->label.empty()) {
            names.push_back(l->label);
            continue;
        }
        const char* kind = l->type() == LightType::DeltaPosition    ? "point-like"
                           : l->type() == LightType::DeltaDirection ? "distant"
                                                                    : "infinite";
        names.push_back("light #" + std::to_string(l->index) + " (" + kind + ")");
    }
    return listed(names);
}

std::string materialNames(const std::vector<const Material*>& materials) {
    std::vector<std::string> names;
    for (const Material* m : materials) names.push_back(m->label.empty() ? "an unnamed specular material" : m->label);
    return listed(names);
}

std::string cameraName(const Camera& camera) {
    const Camera::Params& p = camera.params();
    switch (p.projection) {
        case Camera::Projection::Perspective:
            if (p.lensRadius > 0) {
                char r[32];
                std::snprintf(r, sizeof r, "%g", double(p.lensRadius));
                return std::string("the thin-lens camera (lensradius ") + r + ")";
            }
            return "the pinhole camera (perspective, lensradius 0)";
        case Camera::Projection::Orthographic: return "the orthographic camera";
        case Camera::Projection::Spherical: return "the spherical camera";
        case Camera::Projection::Realistic: return "the realistic camera";
    }
    return "the camera";
}

// --mlt-direct's samples per pixel (0: the chains render every path); a spec the integrator
// will refuse counts as 0.
double mltDirectSamples(const Scene& scene) {
    try {
        return parseMutationWeights(scene.settings().mltMutations).direct;
    } catch (const InputError&) {
        return 0;
    }
}

constexpr const char* kRemedies =
    "Veach's remedies: a small area light instead of the delta light, a roughness floor on the specular materials "
    "(e.g. \"float roughness\" 0.01), or a finite aperture (Camera \"float lensradius\" > 0) rendered with bdpt, "
    "light, pssmlt or mlt, whose t = 0 strategy samples these paths";

// Class (a): L S+ E from a delta light, through a camera that no light subpath can hit
// (thesis §1.1: no unbiased technique samples them).
std::optional<UnsampledPaths> deltaSpecularEye(const Scene& scene, const SceneTraits& t, const std::string& integrator) {
    if (t.delta.empty() || t.specular.empty() || samplesLensHits(scene, integrator)) return std::nullopt;
    const bool every = !samplesLensHits(scene, "bdpt");
    // mlt through a lens misses them only where --mlt-direct gives its one-bounce paths to the
    // path tracer (the chains still sample L S S+ E).
    const bool mltDirect = integrator == "mlt" && !every;
    return UnsampledPaths{
        "delta-specular-eye",
        "no technique of \"" + integrator + "\" samples the light of " + lightNames(t.delta) + " seen through " +
            materialNames(t.specular) + " by " + cameraName(scene.camera()) + " (L S+ E paths, thesis sec. 1.1): " +
            (every      ? std::string("every integrator renders them black")
             : mltDirect ? std::string("--mlt-direct renders the one-bounce ones (L S E) with the path tracer, which "
                                       "cannot sample them; without it mlt samples them through this lens (t = 0)")
                         : std::string("bdpt, light, pssmlt and mlt sample them through this lens (t = 0)")) +
            ". " + kRemedies,
        every};
}

// Light emitted inside a medium (sigma_a Le, pbrt-v4's volpath) is sampled only by a camera
// walk's free flights: no light sampler chooses points in volumes, so no light subpath starts
// there. Light tracing has no other strategy. Veach's mlt's paths begin with a vertex x0 on a
// light (mlt/veach/path_space.h), which its mutations generate by sampling lights: an
// emitting medium point would be a new kind of x0, with a density none of them has (not
// implemented, rather than impossible as for light tracing).
std::optional<UnsampledPaths> mediumEmission(const Scene& scene, const std::string& integrator) {
    if ((integrator != "light" && integrator != "mlt") || !scene.hasEmissiveMedia()) return std::nullopt;
    const std::string why =
        integrator == "light"
            ? "light tracing cannot render light emitted inside a medium: its only subpaths start on lights, and "
              "no light sampler chooses points in volumes (only a camera walk's free flights find that emission)"
            : "Veach's mlt cannot render light emitted inside a medium: its paths begin at a vertex on a light, "
              "which its mutations sample from the lights, and no light sampler chooses points in volumes (an emitting "
              "medium point as a path's first vertex is not implemented)";
    return UnsampledPaths{"medium-emission", why + "; use path, bdpt, pssmlt or mmlt", false};
}

}  // namespace

bool samplesLensHits(const Scene& scene, const std::string& integrator) {
    // pssmlt mutates BDPT's samples, all strategies at once, t = 0 included (BDPTIntegrator::
    // lensHits); Veach's mlt generates the lens vertex from the light side in its bootstrap
    // and its bidirectional mutation (PathSpace::reachLens); mmlt samples one strategy with
    // t >= 1 at a time. In media too: the light walks' free flights reach the lens
    // (subpaths_media.cpp, PathSpace::trace).
    if (integrator == "mlt") return scene.camera().hasLensDisk() && mltDirectSamples(scene) == 0;
    return (integrator == "bdpt" || integrator == "light" || integrator == "pssmlt") && scene.camera().hasLensDisk();
}

std::vector<UnsampledPaths> unsampledPaths(const Scene& scene, const std::string& integrator) {
    std::vector<UnsampledPaths> out;
    // Nothing reaches a camera without importance: the one class says all.
    if ((integrator == "light" || integrator == "mlt") && !scene.camera().hasImportance())
        return {{integrator + "-lens", "it " + lensRequirement(integrator)}};
    const SceneTraits t = traitsOf(scene);
    if (integrator == "path" && !t.delta.empty() && !t.specular.empty())
        out.push_back({"delta-caustic",
                       "path tracing cannot reach a point, spot, goniometric, projection or distant light through a "
                       "specular surface (their caustics are black); use bdpt (lights: " + lightNames(t.delta) +
                           "; specular: " + materialNames(t.specular) + ")"});
    if (integrator == "light") {
        if (!t.infinite.empty())
            out.push_back({"light-environment", "light tracing cannot show the environment seen directly; use path or "
                                                "bdpt (" + lightNames(t.infinite) + ")"});
        // Unbiased, but a scattering point at distance d from the lens contributes 1/d^2, whose
        // square a volume around the lens does not integrate: the render never converges.
        if (scene.cameraMedium())
            out.push_back({"light-camera-medium", "light tracing from scattering points around a camera in a medium has "
                                                  "unbounded variance; use path or bdpt"});
        if (!t.specular.empty() && !samplesLensHits(scene, integrator))
            out.push_back({"light-specular", "light tracing cannot show what the camera sees in a specular surface "
                                             "(mirror, smooth glass or coating); use path or bdpt (specular: " +
                                                 materialNames(t.specular) + "; " + cameraName(scene.camera()) +
                                                 "; with a thin lens, light tracing's t = 0 strategy would)"});
    }
    if (auto a = deltaSpecularEye(scene, t, integrator)) out.push_back(*a);
    if (auto e = mediumEmission(scene, integrator)) out.push_back(*e);
    return out;
}

std::string inconsistentSurfaces(const Scene& scene, const std::string& integrator) {
    if (integrator == "path") return "";
    for (const Shape* shape : scene.shapes()) {
        const auto* curve = dynamic_cast<const Curve*>(shape);
        if (!curve || curve->type() == CurveType::Ribbon || !shape->material ||
            dynamic_cast<const HairMaterial*>(shape->material))
            continue;
        return "flat and cylinder curves turn to face each ray, so light paths meet them other than camera rays do; "
               "with a material other than hair only path tracing renders them consistently (as in pbrt-v4): use "
               "path, hair, or ribbon curves";
    }
    return "";
}

std::string lensRequirement(const std::string& integrator) {
    return integrator == "light" ? "connects every light path to the lens and needs a perspective camera"
                                 : "mutates paths through the lens and needs a perspective camera";
}

std::string missingPaths(const Scene& scene, const std::string& integrator) {
    for (const UnsampledPaths& c : unsampledPaths(scene, integrator))
        if (!c.everyIntegrator) return c.message;
    return "";
}

std::string unsupportedMedia(const Scene& scene, const std::string& integrator) {
    // Refused rather than rendered without the emission (it would be an image darker than
    // every other integrator's, unsampled-paths' warning alone is too easy to miss).
    if (auto e = mediumEmission(scene, integrator)) return e->message;
    return "";
}

}  // namespace ps
