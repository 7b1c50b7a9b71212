// A medium whose coefficients are constant spectra sigma_a and sigma_s times a scalar density
// field inside a box (pbrt-v4's CloudMedium and NanoVDBMedium alike): the point's density in
// the medium's space scales both, and tracking walks a majorant grid of the density's bounds
// over the box times sigma_a + sigma_s. Subclasses give the density and fill the grid.
#pragma once
#include <atomic>
#include <cstdint>
#include "media/majorant_grid.h"

namespace ps {

class DensityMedium : public Medium {
public:
    DensityMedium(const MediumBox& box, MediumSpectrum sigmaA, MediumSpectrum sigmaS, float g, int majorantRes)
        : Medium(g), box_(box), sigmaA_(std::move(sigmaA)), sigmaS_(std::move(sigmaS)),
          majorants_(majorantRes, majorantRes, majorantRes) {
        static std::atomic<uint64_t> count{0};
        serial_ = ++count;
    }

    // The density at a point of the medium's space.
    virtual float density(Vec3 pMedium) const = 0;

    // The emitted radiance Le at a point of the medium's space (emissive media only).
    virtual Spectrum emission(Vec3 /*pMedium*/, const SampledWavelengths* /*lambda*/) const { return {}; }

    MediumProperties at(Vec3 p, const SampledWavelengths* lambda) const final { return at(p, sigmaA(lambda), sigmaS(lambda), lambda); }
    MajorantIterator majorants(Vec3 o, Vec3 d, float tMax, const SampledWavelengths* lambda) const final {
        return majorants(o, d, tMax, sigmaA(lambda) + sigmaS(lambda));
    }
    const DensityMedium* asDensityMedium() const final { return this; }
    // Unique among all density media made by the process (never 0).
    uint64_t serial() const { return serial_; }

    // The same given sigma_a and sigma_s at the wavelengths (media/medium_lookup.h evaluates
    // them once per ray).
    Spectrum sigmaA(const SampledWavelengths* lambda) const { return sigmaA_(lambda); }
    Spectrum sigmaS(const SampledWavelengths* lambda) const { return sigmaS_(lambda); }
    MediumProperties at(Vec3 p, const Spectrum& sigmaA, const Spectrum& sigmaS, const SampledWavelengths* lambda) const {
        const Vec3 pm = box_.toMedium(p);
        const float d = density(pm);
        return {sigmaA * d, sigmaS * d, emissive() ? emission(pm, lambda) : Spectrum(0.0f)};
    }
    MajorantIterator majorants(Vec3 o, Vec3 d, float tMax, const Spectrum& sigmaT) const {
        return box_.iterate(o, d, tMax, majorants_, sigmaT);
    }
    const MajorantGrid& majorantGrid() const { return majorants_; }
    const MediumBox& box() const { return box_; }

protected:
    MediumBox box_;
    MediumSpectrum sigmaA_, sigmaS_;
    MajorantGrid majorants_;

private:
    uint64_t serial_ = 0;
};

}  // namespace ps
