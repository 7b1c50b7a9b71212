#include "lights/emission_choice.h"

namespace ps {

std::vector<float> emissionChoiceWeights(std::span<const Light* const> lights, std::span<const float> power,
                                         const LightSampler* sampler, Vec3 eye) {
    std::vector<float> w(power.begin(), power.end());
    if (!sampler) return w;
    // No normal at the eye: the tree counts light arriving from every side.
    const LightSampleContext ctx{eye, Vec3(0, 0, 0), nullptr};
    double boundedPower = 0, boundedChoice = 0;
    std::vector<double> choice(lights.size(), 0.0);
    // Once per light: bounds() may walk an image (projection and goniometric lights).
    std::vector<char> bounded(lights.size(), 0);
    for (size_t i = 0; i < lights.size(); ++i) {
        bounded[i] = lights[i]->bounds().has_value();
        if (!bounded[i]) continue;  // at infinity
        boundedPower += power[i];
        choice[i] = sampler->pmf(ctx, lights[i]);
        boundedChoice += choice[i];
    }
    if (!(boundedPower > 0) || !(boundedChoice > 0)) return w;
    for (size_t i = 0; i < lights.size(); ++i) {
        if (!bounded[i]) continue;
        const double share = (1 - kEmissionPowerShare) * choice[i] / boundedChoice +
                             kEmissionPowerShare * power[i] / boundedPower;
        w[i] = float(share * boundedPower);
    }
    return w;
}

}  // namespace ps
