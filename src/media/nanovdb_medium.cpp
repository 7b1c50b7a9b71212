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
        // The index-space box of the cell's eight corners. A sample at index x blends voxels
        // floor(x) and floor(x) + 1, so the cell's own voxels are floor(min) .. floor(max) + 1.
        // A point that rounding puts up to kSlop voxels outside the cell gives the ring of
        // voxels one beyond them a weight of at most kSlop along each axis, so the bound is
        // the own voxels' largest plus 3 kSlop times the ring's excess over it (pbrt-v4 takes
        // the ring's largest whole, a looser bound). Beyond the index box every voxel is the
        // background.
        constexpr float kSlop = 0.125f;
        float mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int c = 0; c < 8; ++c) {
            const Vec3 u((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
            const Vec3 pi = grid_.worldToIndex(box_.p0 + Vec3(u.x * e.x, u.y * e.y, u.z * e.z));
            for (int a = 0; a < 3; ++a) {
                mn[a] = std::min(mn[a], pi[a]);
                mx[a] = std::max(mx[a], pi[a]);
            }
        }
        float own = 0, all = 0;
        int64_t i0[3], i1[3], own0[3], own1[3];
        for (int a = 0; a < 3; ++a) {
            const float lo0 = std::floor(mn[a]) - 1, hi0 = std::floor(mx[a]) + 2;
            if (std::isnan(lo0) || std::isnan(hi0)) return grid_.maxValue();  // a corrupt map
            if (lo0 < float(iMin[a]) || hi0 > float(iMax[a])) all = std::max(all, grid_.background());
            if (lo0 + 1 < float(iMin[a]) || hi0 - 1 > float(iMax[a])) own = std::max(own, grid_.background());
            // In double and 64 bits: a corrupt map may put the corners far beyond int's range.
            i0[a] = int64_t(std::clamp(double(lo0), double(iMin[a]), double(iMax[a]) + 1));
            i1[a] = int64_t(std::clamp(double(hi0), double(iMin[a]) - 1, double(iMax[a])));
            own0[a] = int64_t(std::clamp(double(lo0) + 1, double(iMin[a]) - 1, double(iMax[a]) + 1));
            own1[a] = int64_t(std::clamp(double(hi0) - 1, double(iMin[a]) - 1, double(iMax[a]) + 1));
        }
        auto bound = [&] { return own + 3 * kSlop * std::max(0.0f, all - own); };
        // A cell over very many voxels (a coarse grid of a huge volume, or a corrupt map):
        // the largest value in the grid bounds it without scanning them.
        const double voxels = double(i1[0] - i0[0] + 1) * double(i1[1] - i0[1] + 1) * double(i1[2] - i0[2] + 1);
        if (voxels > double(1 << 18)) return std::max(all, grid_.maxValue());
        // Block by 8^3 block: one lookup of the block for each.
        for (int64_t k0 = i0[2]; k0 <= i1[2]; k0 = (k0 | 7) + 1)
            for (int64_t j0 = i0[1]; j0 <= i1[1]; j0 = (j0 | 7) + 1)
                for (int64_t x0 = i0[0]; x0 <= i1[0]; x0 = (x0 | 7) + 1) {
                    const NanoVDBGrid::Block b = grid_.block(int(x0), int(j0), int(k0));
                    const int64_t k1 = std::min(i1[2], k0 | 7), j1 = std::min(i1[1], j0 | 7), x1 = std::min(i1[0], x0 | 7);
                    if (!b.leafValues) {
                        // One value over the block's part of the range: its own voxels' if
                        // the part overlaps them.
                        all = std::max(all, b.value);
                        if (std::max(x0, own0[0]) <= std::min(x1, own1[0]) && std::max(j0, own0[1]) <= std::min(j1, own1[1]) &&
                            std::max(k0, own0[2]) <= std::min(k1, own1[2]))
                            own = std::max(own, b.value);
                        continue;
                    }
                    // The leaf's values run z fastest: z innermost, a tight loop over a row.
                    auto rowMax = [&](int64_t i, int64_t j, int64_t kLo, int64_t kHi, float m) {
                        for (int64_t k = kLo; k <= kHi; ++k) m = std::max(m, b.at(int(i), int(j), int(k)));
                        return m;
                    };
                    for (int64_t i = x0; i <= x1; ++i)
                        for (int64_t j = j0; j <= j1; ++j) {
                            all = rowMax(i, j, k0, k1, all);
                            if (i >= own0[0] && i <= own1[0] && j >= own0[1] && j <= own1[1])
                                own = rowMax(i, j, std::max(k0, own0[2]), std::min(k1, own1[2]), own);
                        }
                }
        return bound();
    });
}

float NanoVDBMedium::density(Vec3 pMedium) const { return grid_.sample(grid_.worldToIndex(pMedium)); }

}  // namespace ps
