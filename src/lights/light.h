// Emitters. Integrators sample incident radiance at a point (next-event estimation) and
// ask for the density of the same choice to weight BSDF-sampled hits (thesis ch. 9, MIS).
#pragma once
#include <optional>
#include "geometry/interaction.h"
#include "geometry/ray.h"
#include "math/spectrum.h"

namespace ps {

enum class LightType { DeltaPosition, DeltaDirection, Area, Infinite };

// The receiving point.
struct LightSampleContext {
    Vec3 p;
    Vec3 ng;  // geometric normal at p (for ray offsets)
};

struct LightLiSample {
    Spectrum L;      // radiance arriving at the receiver (intensity/d^2 for point lights)
    Vec3 wi;         // unit direction towards the light
    float pdf = 0;   // solid angle at the receiver; 1 for delta lights
    Vec3 pLight;     // point on the light (far away for distant/infinite lights)
    Vec3 nLight;     // its normal (zero for non-surface lights)
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
    // Area lights: radiance leaving surface point (p, n, uv) in direction w.
    virtual Spectrum L(Vec3 p, Vec3 n, Vec2 uv, Vec3 w) const { (void)p; (void)n; (void)uv; (void)w; return {}; }
    // Infinite lights: radiance arriving along a ray that escapes the scene.
    virtual Spectrum Le(const Ray& r) const { (void)r; return {}; }
    // Emitted power (for choosing lights in proportion to it).
    virtual Spectrum phi() const = 0;
    // Lights that depend on the scene's extent learn it here.
    virtual void preprocess(Vec3 sceneCenter, float sceneRadius) { (void)sceneCenter; (void)sceneRadius; }

    int index = -1;  // position in the scene's light list

private:
    LightType type_;
};

}  // namespace ps
