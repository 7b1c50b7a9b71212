// Choosing one light for next-event estimation (thesis §9: light sampling as one of the
// strategies MIS combines). A LightSampler gives the light and the probability of that
// choice; integrators divide by it, and weight the paths that hit an emitter by it, so
// sample() and pmf() must agree exactly at the same point.
//
// pbrt-v4's choices, by the Integrator's "lightsampler":
//   "uniform": every light alike;
//   "power":   in proportion to emitted power, wherever the receiving point is;
//   "bvh":     in proportion to an estimate of what each light gives the receiving point, by
//              descending a tree over the lights' bounds (bvh_light_sampler.h).
// The context-free choice (no receiving point: light subpaths start here) is by power for
// "power" and "bvh", uniform for "uniform".
#pragma once
#include <memory>
#include <span>
#include <string>
#include <vector>
#include "lights/light.h"
#include "mc/alias_table.h"

namespace ps {

struct SampledLight {
    const Light* light = nullptr;  // null: no light can be chosen (pmf 0)
    float pmf = 0;                 // probability of the choice
};

// The lights a sampler is built over must carry their positions in its list (Light::index,
// as the scene's light list sets it): the samplers find a light's probability by it.
class LightSampler {
public:
    virtual ~LightSampler() = default;
    // A light for the point ctx.p with geometric normal ctx.ng (zero for a point not on a
    // surface), chosen by u in [0, 1).
    virtual SampledLight sample(const LightSampleContext& ctx, float u) const = 0;
    // The probability that sample(ctx, u) chooses light, for uniform u.
    virtual float pmf(const LightSampleContext& ctx, const Light* light) const = 0;
    // The same without a receiving point.
    virtual SampledLight sample(float u) const = 0;
    virtual float pmf(const Light* light) const = 0;
};

// A sampler whose choice does not depend on the receiving point.
class PointFreeLightSampler : public LightSampler {
public:
    SampledLight sample(const LightSampleContext&, float u) const final { return sample(u); }
    float pmf(const LightSampleContext&, const Light* light) const final { return pmf(light); }
    using LightSampler::pmf;
    using LightSampler::sample;
};

class UniformLightSampler final : public PointFreeLightSampler {
public:
    using PointFreeLightSampler::pmf;
    using PointFreeLightSampler::sample;
    explicit UniformLightSampler(std::span<const Light* const> lights);
    SampledLight sample(float u) const override;
    float pmf(const Light* light) const override;

private:
    std::vector<const Light*> lights_;
};

class PowerLightSampler final : public PointFreeLightSampler {
public:
    using PointFreeLightSampler::pmf;
    using PointFreeLightSampler::sample;
    // By the luminance of each light's phi(); all zero: uniform (AliasTable's rule).
    explicit PowerLightSampler(std::span<const Light* const> lights);
    SampledLight sample(float u) const override;
    float pmf(const Light* light) const override;

private:
    std::vector<const Light*> lights_;
    AliasTable table_;
};

// The names createLightSampler knows, for the scene file's errors.
inline constexpr const char* kLightSamplerNames = "\"uniform\", \"power\" or \"bvh\"";
bool isLightSamplerName(const std::string& name);

// The sampler `name` names (isLightSamplerName) over `lights`; throws std::invalid_argument for
// another name.
std::unique_ptr<LightSampler> createLightSampler(const std::string& name, std::span<const Light* const> lights);

// Throws std::invalid_argument unless lights[i]->index == i for every i.
void checkLightIndices(std::span<const Light* const> lights);

}  // namespace ps
