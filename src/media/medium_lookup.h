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
        if (!density_) return;
        // A path keeps its wavelengths and meets few media: the last spectra this thread
        // evaluated are most often these.
        thread_local struct {
            uint64_t medium = 0;  // a serial number: a later medium may reuse an address
            SpectralValues lambda{};
            bool spectral = false;
            Spectrum sigmaA, sigmaS;
        } last;
        const bool spectral = lambda != nullptr;
        if (last.medium != density_->serial() || last.spectral != spectral || (spectral && last.lambda != lambda->lambda)) {
            last.medium = density_->serial();
            last.spectral = spectral;
            if (spectral) last.lambda = lambda->lambda;
            last.sigmaA = density_->sigmaA(lambda);
            last.sigmaS = density_->sigmaS(lambda);
        }
        sigmaA_ = last.sigmaA;
        sigmaS_ = last.sigmaS;
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
