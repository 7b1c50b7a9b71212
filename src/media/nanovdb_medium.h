// pbrt-v4's "nanovdb" medium (media.h: NanoVDBMedium): a float density grid read from a
// NanoVDB file (media/nanovdb_file.h), in the medium's space through the grid's own
// index-to-world map, sampled trilinearly at voxel corners as NanoVDB's SampleFromVoxels order 1.
// sigma_a and sigma_s (times "scale") are multiplied by it; tracking walks a 64^3 majorant grid
// over the grid's world box, pbrt-v4's resolution for this medium.
//
// Emission, as pbrt-v4's NanoVDBMedium::Le: a second float grid of temperatures (sampled
// through its own index map), T = (value - temperatureoffset) * temperaturescale kelvin,
// emits Lescale times the blackbody spectrum of T normalised to a peak of 1 (no photometric
// normalisation, unlike Le of the other media), and nothing at or below 100 K.
#pragma once
#include <optional>
#include <vector>
#include "media/density_medium.h"
#include "media/nanovdb_file.h"
#include "math/transform.h"

namespace ps {

struct NanoVDBTemperature {
    NanoVDBGrid grid;
    float LeScale = 1, offset = 0, scale = 1;
};

class NanoVDBMedium final : public DensityMedium {
public:
    NanoVDBMedium(const Transform& worldFromMedium, NanoVDBGrid density, MediumSpectrum sigmaA, MediumSpectrum sigmaS, float g,
                  std::optional<NanoVDBTemperature> temperature = std::nullopt);

    float density(Vec3 pMedium) const override;
    // pbrt-v4: emissive when it has a temperature grid and Lescale > 0.
    bool emissive() const override { return temperature_ && temperature_->LeScale > 0; }
    Spectrum emission(Vec3 pMedium, const SampledWavelengths* lambda) const override;
    // The temperature in kelvin at a point of the medium's space (0 without a grid).
    float kelvin(Vec3 pMedium) const;
    const NanoVDBGrid& grid() const { return grid_; }

private:
    void buildBlackbodyTable();

    NanoVDBGrid grid_;
    std::optional<NanoVDBTemperature> temperature_;
    // RGB mode: the blackbody's RGB (its chromaticity times its luminance) tabulated from 100 K
    // to the grid's hottest, interpolated linearly (spectral mode evaluates Planck's law).
    std::vector<Spectrum> rgbTable_;
    float tableMax_ = 0;
};

}  // namespace ps
