#include "transport/coverage.h"

#include <set>

#include "geometry/curve.h"
#include "materials/bxdf.h"
#include "materials/hair_material.h"

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

struct SceneTraits {
    bool specular = false, deltaLight = false, infinite = false;
};

SceneTraits traitsOf(const Scene& scene) {
    SceneTraits t;
    std::set<const Material*> seen;
    for (const Shape* shape : scene.shapes())
        if (shape->material && seen.insert(shape->material).second)
            t.specular = t.specular || mayScatterSpecularly(*shape->material);
    for (const auto& light : scene.lights()) {
        t.deltaLight = t.deltaLight || light->type() == LightType::DeltaPosition || light->type() == LightType::DeltaDirection;
        t.infinite = t.infinite || light->type() == LightType::Infinite;
    }
    return t;
}

}  // namespace

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
    if ((integrator == "light" || integrator == "mlt") && !scene.camera().hasImportance())
        return "it " + lensRequirement(integrator);
    if (integrator != "light" && integrator != "path") return "";
    const SceneTraits t = traitsOf(scene);
    if (integrator == "path")
        return t.deltaLight && t.specular
                   ? "path tracing cannot reach a point, spot, goniometric, projection or distant light through a "
                     "specular surface (their caustics are black); use bdpt"
                   : "";
    if (t.infinite) return "light tracing cannot show the environment seen directly; use path or bdpt";
    // Unbiased, but a scattering point at distance d from the lens contributes 1/d^2, whose
    // square a volume around the lens does not integrate: the render never converges.
    if (scene.cameraMedium())
        return "light tracing from scattering points around a camera in a medium has unbounded variance; use path or "
               "bdpt";
    if (t.specular)
        return "light tracing cannot show what the camera sees in a specular surface (mirror, smooth glass or "
               "coating); use path or bdpt";
    return "";
}

std::string unsupportedMedia(const Scene& scene, const std::string& integrator) {
    if (!scene.hasMedia() || integrator == "path") return "";
    // Medium vertices carry no emission (Veach's mlt's included): sigma_a Le is only path tracing's.
    if (scene.hasEmissiveMedia())
        return "integrator \"" + integrator + "\" does not support emissive media yet; render this scene with \"path\" "
               "(pbrt-v4's \"volpath\")";
    return "";
}

}  // namespace ps
