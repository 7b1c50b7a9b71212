// The renderable scene: Embree BVH over shapes and instances, materials, lights with a
// power-proportional light chooser and the scene's light sampler (which may choose by the
// receiving point), the camera and the render settings from the file.
#pragma once
#include <optional>
#include <array>
#include <embree3/rtcore.h>
#include <limits>
#include <memory>
#include <string>
#include <vector>
#include "camera/camera.h"
#include "film/filter.h"
#include "film/film.h"
#include "geometry/shape.h"
#include "lights/light.h"
#include "lights/light_sampler.h"
#include "mc/alias_table.h"
#include "materials/material.h"
#include "media/medium.h"
#include "util/error.h"

namespace ps {

// What the scene file asks for; the command line may override each field.
struct RenderSettings {
    std::string integrator = "path";
    std::string sceneIntegrator;  // the scene's Integrator type as written ("mlt" runs our "mmlt")
    int maxDepth = 5;
    bool regularize = false;
    std::string lightSampler = "bvh";  // Integrator "lightsampler" (isLightSamplerName)
    std::string sampler = "sobol";
    int spp = 16;
    uint64_t seed = 0;
    std::string outputFile = "pbrt.exr";
    float imagingRatio = 1;  // (shutterclose - shutteropen) * iso / 100
    float maxComponentValue = std::numeric_limits<float>::infinity();  // Film "maxcomponentvalue"
    // Markov-chain integrators (pssmlt, mmlt), with pbrt-v4's parameter names and defaults.
    int mltBootstrapSamples = 100000;  // "bootstrapsamples"
    int mltChains = 1000;              // "chains"
    float mltLargeStepProbability = 0.3f;  // "largestepprobability"
    float mltSigma = 0.01f;                // "sigma"
    float mltCameraStepProbability = 0.5f; // --camera-step-probability (no pbrt-v4 parameter)
    float mltStrategyPilot = 0.1f;         // mmlt: the bootstrap's share spent on its pilot
    float mltTwoStage = -1;                // --two-stage: the pilot image's samples per bootstrap sample
                                           // (below 0: the integrator's default, metropolisTwoStage)
    float mltTwoStageBlackLevel = 0.1f;    // --two-stage-black-level: pixel luminance
    float bdptLightPaths = 1;  // --light-paths: BDPT's light subpaths per camera sample, in (0, 1]
    bool bdptLightPathsAuto = false;  // --light-paths auto: bdptLightPaths is the pilot's choice, in [0, 1]
    double bdptPilotPath = 0, bdptPilotBdpt = 0;  // its figures (LightPathChoice)
    int lightSamples = 1;      // --light-samples: the path tracer's light samples per vertex
    std::string mltMutations;              // mlt: the mutations' weights, "KEY=VALUE,..." (--mlt-mutations)
    SourceLoc filmLoc;       // the Film directive, for errors found when the film is made
    SourceLoc cameraLoc;     // the Camera directive
    // The film's ColorSpace, when not sRGB: the image's RGB from the rendering space's
    // (row-major). The variance image stays the rendering space's luminance variance.
    std::optional<std::array<float, 9>> outputColorMatrix;
    // `--color spectral`: paths carry sampled wavelengths and the film's sensor makes colour
    // (transport/spectral_film.h); false: RGB mode.
    bool spectral = false;
    const RGBColorSpace* filmColorSpace = nullptr;  // the Film's ColorSpace (null: sRGB)
    float whiteBalance = 0;  // Film "whitebalance" (kelvin, 0: none), applied in spectral mode
};

class Scene {
public:
    Scene();
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    // Closest hit within r.tMax at time r.time; fills si (geometry, material, emitter, wo).
    bool intersect(const Ray& r, SurfaceInteraction& si) const;
    // Any hit within r.tMax.
    bool occluded(const Ray& r) const;

    // The choice of the light that starts a light subpath (lights/emission_choice.h: by power,
    // or with the light BVH mostly by what each light sends to the camera's position).
    const Light* sampleLight(float u, float* pmf) const;
    float lightPmf(const Light* light) const;
    // The choice the scene's "lightsampler" names, which may depend on the receiving point
    // (the path tracer's next-event estimation and its MIS weights use it).
    const LightSampler& lightSampler() const { return *lightSampler_; }

    const std::vector<std::unique_ptr<Light>>& lights() const { return lights_; }
    const std::vector<const Light*>& infiniteLights() const { return infiniteLights_; }
    const std::vector<std::shared_ptr<Material>>& materials() const { return materials_; }
    // Every shape rays can hit, instanced ones included (`interface` shapes only in scenes with media).
    std::vector<const Shape*> shapes() const {
        std::vector<const Shape*> v;
        for (const auto& s : shapes_) v.push_back(s.get());
        return v;
    }
    // Participating media: whether any shape or the camera is in one (then `interface`
    // shapes are in the BVH, and shadow rays go through Transmittance, not occluded()), and
    // the camera's medium (pbrt-v4's CameraMedium; null: vacuum).
    bool hasMedia() const { return hasMedia_; }
    const Medium* cameraMedium() const { return cameraMedium_; }
    bool hasEmissiveMedia() const {
        for (const auto& m : media_)
            if (m->emissive()) return true;
        return false;
    }
    const Camera& camera() const { return *camera_; }
    Camera& camera() { return *camera_; }
    const Filter& filter() const { return *filter_; }
    const PixelBounds& pixelBounds() const { return pixelBounds_; }
    void setPixelBounds(const PixelBounds& b) { pixelBounds_ = b; }
    void setCamera(std::unique_ptr<Camera> c) { camera_ = std::move(c); }
    void setFilter(std::unique_ptr<Filter> f) { filter_ = std::move(f); }
    // Motion blur: something moves (geometry, or the camera), so each path draws its time.
    bool hasMotion() const { return geometryMoves_ || (camera_ && camera_->isMoving()); }
    const RenderSettings& settings() const { return settings_; }
    RenderSettings& settings() { return settings_; }
    Vec3 boundsCenter() const { return center_; }
    // The underlying Embree scene, for benchmarks that measure raw traversal speed.
    RTCScene embreeScene() const { return scene_; }
    float boundsRadius() const { return radius_; }

private:
    friend class SceneBuilder;
    struct Instance {
        Transform worldFromPrototype;
        int prototype;
        // A moving instance: world-from-prototype at time t is motion(t) * objectFromPrototype
        // (the inverse of EmbreeMotion's constant C), what Embree interpolates.
        AnimatedTransform motion;
        Transform objectFromPrototype;
    };
    // Embree's time in [0,1] for a scene time: TransformTimes' interval, clamped as pbrt-v4's
    // AnimatedTransform clamps; 0 without moving geometry (no time in the rays' bits).
    float embreeTime(float time) const {
        return geometryMoves_ ? keyframeFraction(time, motionStart_, motionEnd_) : 0.0f;
    }

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<RTCScene> prototypeScenes_;
    std::vector<std::unique_ptr<Shape>> shapes_;          // owns every shape
    std::vector<const Shape*> worldGeometry_;             // by world geomID (nullptr: instance)
    std::vector<int> instanceOfGeometry_;                 // by world geomID: index into instances_, or -1
    std::vector<Instance> instances_;
    std::vector<std::vector<const Shape*>> prototypeGeometry_;  // by prototype, by geomID
    std::vector<std::shared_ptr<Material>> materials_;
    std::vector<std::unique_ptr<Medium>> media_;
    const Medium* cameraMedium_ = nullptr;
    bool hasMedia_ = false;
    std::vector<std::unique_ptr<Light>> lights_;
    std::vector<const Light*> infiniteLights_;
    AliasTable lightDistribution_;  // light subpaths' choice (emission_choice.h)
    std::unique_ptr<LightSampler> lightSampler_;  // always set once the scene is built
    std::unique_ptr<Camera> camera_;
    std::unique_ptr<Filter> filter_;
    PixelBounds pixelBounds_;
    RenderSettings settings_;
    Vec3 center_;
    float radius_ = 1;
    bool geometryMoves_ = false;
    float motionStart_ = 0, motionEnd_ = 1;  // TransformTimes
};

}  // namespace ps
