// Emitters. Integrators sample incident radiance at a point (next-event estimation) and
// ask for the density of the same choice to weight BSDF-sampled hits (thesis ch. 9, MIS).
#pragma once
#include <cmath>
#include <optional>
#include <string>
#include "geometry/interaction.h"
#include "geometry/ray.h"
#include "math/spectrum.h"
#include "lights/light_bounds.h"
#include "lights/light_spectrum.h"

namespace ps {

class Medium;

enum class LightType { DeltaPosition, DeltaDirection, Area, Infinite };

// The receiving point.
struct LightSampleContext {
    Vec3 p;
    Vec3 ng;  // geometric normal at p (for ray offsets)
    // Spectral mode: the path's wavelengths, at which sampleLi returns L (null: RGB).
    const SampledWavelengths* lambda = nullptr;
};

struct LightLiSample {
    Spectrum L;      // radiance arriving at the receiver (intensity/d^2 for point lights)
    Vec3 wi;         // unit direction towards the light
    float pdf = 0;   // solid angle at the receiver; 1 for delta lights
    Vec3 pLight;     // point on the light (far away for distant/infinite lights)
    Vec3 nLight;     // its normal (zero for non-surface lights)
    // Area lights: pdfLe's densities for the reverse ray from pLight along -wi (the area
    // density of pLight and the solid-angle density of -wi), which BDPT's weights need; both
    // zero where a light does not give them.
    float pdfEmitPos = 0, pdfEmitDir = 0;
};

// A ray leaving a light (light tracing and BDPT start their subpaths here, thesis §10.2).
struct LightLeSample {
    Spectrum L;       // radiance along the ray (area, infinite, distant) or intensity (point, spot)
    Ray ray;          // unit direction; for lights at infinity the origin is on a disk
                      // tangent to the scene's bounding sphere, facing along ray.d
    Vec3 n;           // surface normal at the origin (area lights); zero otherwise
    float pdfPos = 0; // area density of the origin (1 for delta positions)
    float pdfDir = 0; // solid-angle density of the direction (1 for delta directions)
    Vec2 uv;          // area lights: the surface parameters of the origin (textured emission)
};

class Light {
public:
    explicit Light(LightType type) : type_(type) {}
    virtual ~Light() = default;
    LightType type() const { return type_; }
    bool isDelta() const { return type_ == LightType::DeltaPosition || type_ == LightType::DeltaDirection; }

    virtual std::optional<LightLiSample> sampleLi(const LightSampleContext& ctx, Vec2 u) const = 0;
    // Solid-angle density of sampleLi choosing direction wi and reaching the surface point
    // `hit` (area lights) or the environment (infinite lights: hit is null).
    virtual float pdfLi(const LightSampleContext& ctx, Vec3 wi, const SurfaceInteraction* hit) const {
        (void)ctx; (void)wi; (void)hit;
        return 0;
    }
    // Radiance leaving surface point (p, n, uv) of an area light in direction w; for point
    // and spot lights, the intensity towards w. At lambda in spectral mode (null: RGB).
    virtual Spectrum L(Vec3 p, Vec3 n, Vec2 uv, Vec3 w, const SampledWavelengths* lambda) const {
        (void)p; (void)n; (void)uv; (void)w; (void)lambda;
        return {};
    }
    // Infinite lights: radiance arriving along a ray that escapes the scene.
    virtual Spectrum Le(const Ray& r, const SampledWavelengths* lambda) const { (void)r; (void)lambda; return {}; }
    // Samples an emitted ray (uPos picks the origin, uDir the direction); L at lambda in
    // spectral mode (null: RGB). The ray's choice does not depend on lambda.
    virtual std::optional<LightLeSample> sampleLe(Vec2 uPos, Vec2 uDir, const SampledWavelengths* lambda) const = 0;
    // Densities of sampleLe choosing the ray leaving p (normal n) along unit direction w.
    // Lights at infinity ignore p and n: pdfPos is the disk's, pdfDir that of -w's choice.
    virtual void pdfLe(Vec3 p, Vec3 n, Vec3 w, float* pdfPos, float* pdfDir) const {
        (void)p; (void)n; (void)w;
        *pdfPos = *pdfDir = 0;
    }
    // True for lights infinitely far away (infinite and distant): their subpaths start on a
    // disk at infinity, and their connections carry no 1/d^2.
    bool atInfinity() const { return type_ == LightType::Infinite || type_ == LightType::DeltaDirection; }
    // Emitted power (for choosing lights in proportion to it), RGB in both colour modes.
    virtual Spectrum phi() const = 0;
    // Where and which way the light emits, for choosing among lights by how much each may
    // give a point (lights/light_sampler.h). None for lights at infinity (infinite and
    // distant), which are chosen apart from the bounded ones.
    virtual std::optional<LightBounds> bounds() const { return std::nullopt; }
    // Lights that depend on the scene's extent learn it here.
    virtual void preprocess(Vec3 sceneCenter, float sceneRadius) { (void)sceneCenter; (void)sceneRadius; }

    int index = -1;  // position in the scene's light list
    // Its scene directive for messages, e.g. `LightSource "point" at scene.pbrt:12:1` (empty
    // for a light made in code: messages then name its index and type).
    std::string label;
    // The media either side of the light (pbrt-v4 gives a light the MediumInterface current
    // at its definition, an area light its shape's): where a light subpath starts.
    const Medium* mediumInside = nullptr;
    const Medium* mediumOutside = nullptr;
    const Medium* mediumToward(Vec3 n, Vec3 w) const { return dot(n, w) < 0 ? mediumInside : mediumOutside; }

private:
    LightType type_;
};

// The incident light at ctx from a point light at pos whose intensity towards world
// direction w is intensity(w): I / d^2 from the light's direction (a delta in solid angle).
template <typename Intensity>
std::optional<LightLiSample> pointLightLi(Vec3 pos, const LightSampleContext& ctx, Intensity&& intensity) {
    Vec3 d = pos - ctx.p;
    float d2 = lengthSquared(d);
    if (!(d2 > 0)) return std::nullopt;
    Vec3 wi = d / std::sqrt(d2);
    Spectrum I = intensity(-wi);
    if (I.isBlack()) return std::nullopt;
    return LightLiSample{I / d2, wi, 1.0f, pos, {}};
}

}  // namespace ps
