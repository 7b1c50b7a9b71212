// pbrt-v4's "nanovdb" medium (media.h: NanoVDBMedium): a float density grid read from a
// NanoVDB file (media/nanovdb_file.h), in the medium's space through the grid's own
// index-to-world map, sampled trilinearly at voxel corners as NanoVDB's SampleFromVoxels order 1.
// sigma_a and sigma_s (times "scale") are multiplied by it; tracking walks a 64^3 majorant grid
// over the grid's world box, pbrt-v4's resolution for this medium.
#pragma once
#include "media/majorant_grid.h"
#include "media/nanovdb_file.h"
#include "math/transform.h"

namespace ps {

class NanoVDBMedium final : public Medium {
public:
    NanoVDBMedium(const Transform& worldFromMedium, NanoVDBGrid density, MediumSpectrum sigmaA, MediumSpectrum sigmaS, float g);

    float density(Vec3 pMedium) const;
    MediumProperties at(Vec3 p, const SampledWavelengths* lambda) const override;
    MajorantIterator majorants(Vec3 o, Vec3 d, float tMax, const SampledWavelengths* lambda) const override;
    const MajorantGrid& majorantGrid() const { return majorants_; }
    const MediumBox& box() const { return box_; }

private:
    NanoVDBGrid grid_;
    MediumBox box_;
    MediumSpectrum sigmaA_, sigmaS_;
    MajorantGrid majorants_{64, 64, 64};
};

}  // namespace ps
