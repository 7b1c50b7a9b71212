// A medium's coefficients and majorants along one ray at one set of wavelengths. A
// DensityMedium's sigma_a and sigma_s are the same spectra times the density everywhere, so
// they are evaluated once here rather than at every collision (in spectral mode each is an
// RGB lifted to the wavelengths, dearer than the density lookup itself).
#pragma once
#include "media/density_medium.h"

namespace ps {

class MediumLookup {
public:
    MediumLookup(const Medium& medium, const SampledWavelengths* lambda)
        : medium_(medium), density_(medium.asDensityMedium()), lambda_(lambda) {
        if (density_) {
            sigmaA_ = density_->sigmaA(lambda);
            sigmaS_ = density_->sigmaS(lambda);
        }
    }
    MediumProperties at(Vec3 p) const { return density_ ? density_->at(p, sigmaA_, sigmaS_, lambda_) : medium_.at(p, lambda_); }
    MajorantIterator majorants(Vec3 o, Vec3 d, float tMax) const {
        return density_ ? density_->majorants(o, d, tMax, sigmaA_ + sigmaS_) : medium_.majorants(o, d, tMax, lambda_);
    }

private:
    const Medium& medium_;
    const DensityMedium* density_;
    const SampledWavelengths* lambda_;
    Spectrum sigmaA_, sigmaS_;
};

}  // namespace ps
