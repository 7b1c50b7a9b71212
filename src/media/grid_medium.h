// pbrt-v4's grid media, placed by the CTM at MakeNamedMedium in the box p0..p1:
// "uniformgrid" (a density grid scaling constant sigma_a and sigma_s, optional Le with a
// "Lescale" grid) and "rgbgrid" (per-voxel RGB sigma_a and sigma_s). Voxel values sit at cell
// centres and are interpolated trilinearly, zero beyond the grid, as pbrt-v4's SampledGrid.
// One majorant bounds the whole box (pbrt-v4 keeps a 16^3 majorant grid; a single bound is
// as unbiased and only costs more null collisions in sparse grids).
#pragma once
#include <vector>
#include "math/transform.h"
#include "media/medium.h"

namespace ps {

struct RGBColorSpace;

template <typename T>
struct VoxelGrid {
    int nx = 1, ny = 1, nz = 1;
    std::vector<T> values;
    // p in [0,1]^3 over the box; convert maps a stored value to the interpolated type.
    template <typename F>
    auto lookup(Vec3 p, F&& convert) const -> decltype(convert(values[0]));
};

class GridMedium final : public Medium {
public:
    struct Box {
        Transform worldFromMedium;
        Vec3 p0, p1;
    };
    // uniformgrid
    GridMedium(const Box& box, VoxelGrid<float> density, MediumSpectrum sigmaA, MediumSpectrum sigmaS,
               MediumSpectrum Le, VoxelGrid<float> LeScale, float g);
    // rgbgrid: an empty grid is 1 everywhere (pbrt-v4's default); values already scaled.
    GridMedium(const Box& box, VoxelGrid<Spectrum> sigmaA, VoxelGrid<Spectrum> sigmaS, const RGBColorSpace* space, float g);

    bool emissive() const override { return emissive_; }
    MediumProperties at(Vec3 p, const SampledWavelengths* lambda) const override;
    bool segment(Vec3 o, Vec3 d, float tMax, const SampledWavelengths* lambda, MajorantSegment* seg) const override;

private:
    Vec3 toUnit(Vec3 pWorld) const;

    Box box_;
    Transform mediumFromWorld_;
    bool rgb_ = false, emissive_ = false;
    VoxelGrid<float> density_, LeScale_;
    MediumSpectrum sigmaA_, sigmaS_, Le_;
    float maxDensity_ = 0;
    VoxelGrid<Spectrum> rgbA_, rgbS_;
    const RGBColorSpace* space_ = nullptr;
    Spectrum rgbMajorant_;      // RGB mode: per channel
    float spectralMajorant_ = 0;  // spectral mode: a bound on every lifted voxel's a + s
};

}  // namespace ps
