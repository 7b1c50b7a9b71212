#include "media/nanovdb_medium.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace ps {

NanoVDBMedium::NanoVDBMedium(const Transform& worldFromMedium, NanoVDBGrid density, MediumSpectrum sigmaA,
                             MediumSpectrum sigmaS, float g, std::optional<NanoVDBTemperature> temperature)
    // The medium's box is the grid's world box, as pbrt-v4's; 64^3 majorant cells, as pbrt-v4's.
    : DensityMedium(MediumBox{worldFromMedium.inverse(), density.worldMin(), density.worldMax()}, std::move(sigmaA),
                    std::move(sigmaS), g, 64),
      grid_(std::move(density)), temperature_(std::move(temperature)) {
    buildBlackbodyTable();
    const Vec3 e = box_.p1 - box_.p0;
    if (!(e.x > 0 && e.y > 0 && e.z > 0))
        throw std::runtime_error(grid_.name() + ": the grid's world bounding box is empty");
    const int* iMin = grid_.indexMin();
    const int* iMax = grid_.indexMax();
    majorants_.fill([&](Vec3 lo, Vec3 hi) {
        // The index-space box of the cell's eight corners; a sample at index x blends voxels
        // floor(x) and floor(x) + 1, and one voxel of slack each way covers rounding (pbrt-v4's
        // "filter slop"). Beyond the grid's index box every voxel is the background.
        float mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int c = 0; c < 8; ++c) {
            const Vec3 u((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
            const Vec3 pi = grid_.worldToIndex(box_.p0 + Vec3(u.x * e.x, u.y * e.y, u.z * e.z));
            for (int a = 0; a < 3; ++a) {
                mn[a] = std::min(mn[a], pi[a]);
                mx[a] = std::max(mx[a], pi[a]);
            }
        }
        float m = 0;
        int64_t i0[3], i1[3];
        for (int a = 0; a < 3; ++a) {
            const float lo0 = std::floor(mn[a]) - 1, hi0 = std::floor(mx[a]) + 2;
            if (std::isnan(lo0) || std::isnan(hi0)) return grid_.maxValue();  // a corrupt map
            if (lo0 < float(iMin[a]) || hi0 > float(iMax[a])) m = std::max(m, grid_.background());
            // In double and 64 bits: a corrupt map may put the corners far beyond int's range.
            i0[a] = int64_t(std::clamp(double(lo0), double(iMin[a]), double(iMax[a]) + 1));
            i1[a] = int64_t(std::clamp(double(hi0), double(iMin[a]) - 1, double(iMax[a])));
        }
        // A cell over very many voxels (a coarse grid of a huge volume, or a corrupt map):
        // the largest value in the grid bounds it without scanning them.
        const double voxels = double(i1[0] - i0[0] + 1) * double(i1[1] - i0[1] + 1) * double(i1[2] - i0[2] + 1);
        if (voxels > double(1 << 18)) return std::max(m, grid_.maxValue());
        // Block by 8^3 block: one descent of the tree for each.
        for (int64_t k0 = i0[2]; k0 <= i1[2]; k0 = (k0 | 7) + 1)
            for (int64_t j0 = i0[1]; j0 <= i1[1]; j0 = (j0 | 7) + 1)
                for (int64_t x0 = i0[0]; x0 <= i1[0]; x0 = (x0 | 7) + 1) {
                    const NanoVDBGrid::Block b = grid_.block(int(x0), int(j0), int(k0));
                    if (!b.leafValues) {
                        m = std::max(m, b.value);
                        continue;
                    }
                    for (int64_t k = k0; k <= std::min(i1[2], k0 | 7); ++k)
                        for (int64_t j = j0; j <= std::min(i1[1], j0 | 7); ++j)
                            for (int64_t i = x0; i <= std::min(i1[0], x0 | 7); ++i)
                                m = std::max(m, b.at(int(i), int(j), int(k)));
                }
        return m;
    });
}

float NanoVDBMedium::density(Vec3 pMedium) const { return grid_.sample(grid_.worldToIndex(pMedium)); }

}  // namespace ps
