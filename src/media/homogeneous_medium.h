// pbrt-v4's "homogeneous" medium: constant sigma_a, sigma_s (times "scale") and Le (times
// "Lescale", over the spectrum's photometric integral) everywhere along a ray in it.
#pragma once
#include "media/majorant_grid.h"

namespace ps {

class HomogeneousMedium final : public Medium {
public:
    HomogeneousMedium(MediumSpectrum sigmaA, MediumSpectrum sigmaS, MediumSpectrum Le, float g)
        : Medium(g), sigmaA_(std::move(sigmaA)), sigmaS_(std::move(sigmaS)), Le_(std::move(Le)) {}
    bool emissive() const override { return Le_.maxValue() > 0; }
    MediumProperties at(Vec3, const SampledWavelengths* lambda) const override {
        return {sigmaA_(lambda), sigmaS_(lambda), Le_(lambda)};
    }
    MajorantIterator majorants(Vec3, Vec3, float tMax, const SampledWavelengths* lambda) const override {
        return MajorantIterator(0, tMax, sigmaA_(lambda) + sigmaS_(lambda));
    }

private:
    MediumSpectrum sigmaA_, sigmaS_, Le_;
};

}  // namespace ps
