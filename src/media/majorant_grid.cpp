#include "media/majorant_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ps {

MajorantIterator::MajorantIterator(const MajorantGrid* grid, Vec3 oUnit, Vec3 dUnit, float t0, float t1, const Spectrum& scale)
    : grid_(grid), tMin_(t0), tMax_(t1), scale_(scale) {
    const Vec3 p = oUnit + dUnit * t0;
    for (int a = 0; a < 3; ++a) {
        const int n = grid->res[a];
        cell_[a] = std::clamp(int(p[a] * n), 0, n - 1);
        if (dUnit[a] == 0) {
            nextCrossing_[a] = std::numeric_limits<float>::infinity();
            deltaT_[a] = 0;
            step_[a] = 0;
            stop_[a] = -2;
        } else if (dUnit[a] > 0) {
            nextCrossing_[a] = t0 + (float(cell_[a] + 1) / n - p[a]) / dUnit[a];
            deltaT_[a] = 1 / (n * dUnit[a]);
            step_[a] = 1;
            stop_[a] = n;
        } else {
            nextCrossing_[a] = t0 + (float(cell_[a]) / n - p[a]) / dUnit[a];
            deltaT_[a] = -1 / (n * dUnit[a]);
            step_[a] = -1;
            stop_[a] = -1;
        }
    }
}

bool MajorantIterator::next(MajorantSegment* seg) {
    if (!(tMin_ < tMax_)) return false;
    if (!grid_) {
        *seg = {tMin_, tMax_, scale_};
        tMin_ = tMax_;
        return true;
    }
    // The axis whose cell boundary the ray reaches first ends this cell's segment.
    int a = 0;
    if (nextCrossing_[1] < nextCrossing_[a]) a = 1;
    if (nextCrossing_[2] < nextCrossing_[a]) a = 2;
    const float tExit = std::min(tMax_, nextCrossing_[a]);
    *seg = {tMin_, tExit, scale_ * grid_->at(cell_[0], cell_[1], cell_[2])};
    tMin_ = tExit;
    if (nextCrossing_[a] >= tMax_) {
        tMin_ = tMax_;
    } else {
        cell_[a] += step_[a];
        if (cell_[a] == stop_[a]) tMin_ = tMax_;
        nextCrossing_[a] += deltaT_[a];
    }
    return true;
}

Vec3 MediumBox::toUnit(Vec3 pWorld) const {
    const Vec3 pm = toMedium(pWorld), e = p1 - p0;
    return {(pm.x - p0.x) / e.x, (pm.y - p0.y) / e.y, (pm.z - p0.z) / e.z};
}

MajorantIterator MediumBox::iterate(Vec3 o, Vec3 d, float tMax, const MajorantGrid& grid, const Spectrum& scale) const {
    // Slabs in the medium's space: the parameter t is the same in both spaces (an affine map),
    // so the clipped interval is in the world ray's distances.
    const Vec3 om = toMedium(o), dm = mediumFromWorld.vector(d);
    float t0 = 0, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        const float inv = 1 / dm[a];
        float tn = (p0[a] - om[a]) * inv, tf = (p1[a] - om[a]) * inv;
        if (tn > tf) std::swap(tn, tf);
        if (std::isnan(tn) || std::isnan(tf)) {  // parallel to the slab and on its plane
            if (om[a] < p0[a] || om[a] > p1[a]) return {};
            continue;
        }
        t0 = std::max(t0, tn);
        t1 = std::min(t1, tf);
        if (t0 > t1) return {};
    }
    const Vec3 e = p1 - p0;
    const Vec3 oUnit{(om.x - p0.x) / e.x, (om.y - p0.y) / e.y, (om.z - p0.z) / e.z};
    const Vec3 dUnit{dm.x / e.x, dm.y / e.y, dm.z / e.z};
    return MajorantIterator(&grid, oUnit, dUnit, t0, t1, scale);
}

}  // namespace ps
