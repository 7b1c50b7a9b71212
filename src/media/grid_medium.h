// pbrt-v4's grid media, placed by the CTM at MakeNamedMedium in the box p0..p1:
// "uniformgrid" (a density grid scaling constant sigma_a and sigma_s, optional Le with a
// "Lescale" grid) and "rgbgrid" (per-voxel RGB sigma_a and sigma_s, optional RGB
// illuminant Le times a scalar "Lescale"). Emission needs no majorant of its own: the tracking
// adds sigma_a Le at the tentative collisions sigma_t's majorant gives. Voxel values sit at cell
// centres and are interpolated trilinearly, zero beyond the grid, as pbrt-v4's SampledGrid.
// Tracking samples against a 16^3 majorant grid over the box, as pbrt-v4's GridMedium and
// RGBGridMedium do.
#pragma once
#include <vector>
#include "media/majorant_grid.h"

namespace ps {

struct RGBColorSpace;

template <typename T>
struct VoxelGrid {
    int nx = 1, ny = 1, nz = 1;
    std::vector<T> values;
    // p in [0,1]^3 over the box; convert maps a stored value to the interpolated type.
    template <typename F>
    auto lookup(Vec3 p, F&& convert) const -> decltype(convert(values[0]));
    // The largest value that lookup can blend at any p in [lo, hi] (unit coordinates), with
    // every value passed through `bound`: a convex blend never exceeds its largest input.
    template <typename R, typename F>
    R maxOver(Vec3 lo, Vec3 hi, F&& bound) const;
};

class GridMedium final : public Medium {
public:
    using Box = MediumBox;
    // uniformgrid
    GridMedium(const Box& box, VoxelGrid<float> density, MediumSpectrum sigmaA, MediumSpectrum sigmaS,
               MediumSpectrum Le, VoxelGrid<float> LeScale, float g);
    // rgbgrid: an empty grid is 1 everywhere (pbrt-v4's default); values already scaled.
    // Le (empty: none): per-voxel RGB illuminants of `space`, times LeScale.
    GridMedium(const Box& box, VoxelGrid<Spectrum> sigmaA, VoxelGrid<Spectrum> sigmaS, const RGBColorSpace* space, float g,
               VoxelGrid<Spectrum> Le = {}, float LeScale = 0);

    bool emissive() const override { return emissive_; }
    MediumProperties at(Vec3 p, const SampledWavelengths* lambda) const override;
    MajorantIterator majorants(Vec3 o, Vec3 d, float tMax, const SampledWavelengths* lambda) const override;
    // The cells' bounds: density (uniformgrid), per-channel RGB sigma_t or its spectral lift's bound (rgbgrid).
    const SpectralMajorantGrid& majorantGrid(bool spectral) const { return spectral && rgb_ ? liftedMajorants_ : majorants_; }

private:
    Box box_;
    bool rgb_ = false, emissive_ = false;
    VoxelGrid<float> density_, LeScale_;
    MediumSpectrum sigmaA_, sigmaS_, Le_;
    VoxelGrid<Spectrum> rgbA_, rgbS_, rgbLe_;
    float rgbLeScale_ = 0;
    const RGBColorSpace* space_ = nullptr;
    // uniformgrid: each cell's largest density. rgbgrid: each cell's largest sigma_a + sigma_s
    // per channel (RGB mode), and a bound on the lifted spectra's (spectral mode).
    SpectralMajorantGrid majorants_{16, 16, 16}, liftedMajorants_;
};

}  // namespace ps
