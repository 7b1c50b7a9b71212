#include "lights/light_sampler.h"

#include <algorithm>
#include <stdexcept>

#include "lights/bvh_light_sampler.h"

namespace ps {

void checkLightIndices(std::span<const Light* const> lights) {
    for (size_t i = 0; i < lights.size(); ++i)
        if (!lights[i] || lights[i]->index != int(i))
            throw std::invalid_argument("light sampler: light " + std::to_string(i) +
                                        " does not carry its position in the list (Light::index)");
}

UniformLightSampler::UniformLightSampler(std::span<const Light* const> lights) : lights_(lights.begin(), lights.end()) {
    checkLightIndices(lights);
}

SampledLight UniformLightSampler::sample(float u) const {
    if (lights_.empty()) return {};
    size_t n = lights_.size();
    size_t i = std::min(size_t(u * float(n)), n - 1);
    return {lights_[i], 1.0f / float(n)};
}

float UniformLightSampler::pmf(const Light* light) const {
    if (!light || light->index < 0 || size_t(light->index) >= lights_.size()) return 0;
    return 1.0f / float(lights_.size());
}

namespace {
std::vector<float> lightPowers(std::span<const Light* const> lights) {
    std::vector<float> power;
    power.reserve(lights.size());
    for (const Light* l : lights) power.push_back(l->phi().luminance());
    return power;
}
}  // namespace

PowerLightSampler::PowerLightSampler(std::span<const Light* const> lights)
    : lights_(lights.begin(), lights.end()), table_(lightPowers(lights)) {
    checkLightIndices(lights);
}

SampledLight PowerLightSampler::sample(float u) const {
    if (lights_.empty()) return {};
    int i = table_.sample(u);
    return {lights_[size_t(i)], table_.pmf(i)};
}

float PowerLightSampler::pmf(const Light* light) const {
    if (!light || light->index < 0 || size_t(light->index) >= lights_.size()) return 0;
    return table_.pmf(light->index);
}

bool isLightSamplerName(const std::string& name) { return name == "uniform" || name == "power" || name == "bvh"; }

std::unique_ptr<LightSampler> createLightSampler(const std::string& name, std::span<const Light* const> lights) {
    if (name == "uniform") return std::make_unique<UniformLightSampler>(lights);
    if (name == "power") return std::make_unique<PowerLightSampler>(lights);
    if (name == "bvh") return std::make_unique<BVHLightSampler>(lights);
    throw std::invalid_argument("unknown light sampler \"" + name + "\" (" + kLightSamplerNames + ")");
}

}  // namespace ps
