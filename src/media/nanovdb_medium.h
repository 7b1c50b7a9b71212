// pbrt-v4's "nanovdb" medium (media.h: NanoVDBMedium): a float density grid read from a
// NanoVDB file (media/nanovdb_file.h), in the medium's space through the grid's own
// index-to-world map, sampled trilinearly at voxel corners as NanoVDB's SampleFromVoxels order 1.
// sigma_a and sigma_s (times "scale") are multiplied by it; tracking walks a 64^3 majorant grid
// over the grid's world box, pbrt-v4's resolution for this medium.
#pragma once
#include "media/density_medium.h"
#include "media/nanovdb_file.h"
#include "math/transform.h"

namespace ps {

class NanoVDBMedium final : public DensityMedium {
public:
    NanoVDBMedium(const Transform& worldFromMedium, NanoVDBGrid density, MediumSpectrum sigmaA, MediumSpectrum sigmaS, float g);

    float density(Vec3 pMedium) const override;

private:
    NanoVDBGrid grid_;
};

}  // namespace ps
