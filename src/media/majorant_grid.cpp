#include "media/majorant_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ps {

MajorantIterator::MajorantIterator(const int res[3], Vec3 oUnit, Vec3 dUnit, float t0, float t1, const Spectrum& scale)
    : tMin_(t0), tMax_(t1), scale_(scale) {
    const Vec3 p = oUnit + dUnit * t0;
    const ptrdiff_t stride[3] = {1, res[0], ptrdiff_t(res[0]) * res[1]};
    for (int a = 0; a < 3; ++a) {
        const int n = res[a];
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
        cellIndex_ += size_t(cell_[a]) * size_t(stride[a]);
        indexStep_[a] = step_[a] * stride[a];
    }
}

bool MajorantIterator::next(MajorantSegment* seg) {
    if (!(tMin_ < tMax_)) return false;
    if (!scalar_ && !spectral_) {
        *seg = {tMin_, tMax_, scale_};
        tMin_ = tMax_;
        return true;
    }
    // The axis whose cell boundary the ray reaches first ends this cell's segment.
    int a = 0;
    if (nextCrossing_[1] < nextCrossing_[a]) a = 1;
    if (nextCrossing_[2] < nextCrossing_[a]) a = 2;
    const float tExit = std::min(tMax_, nextCrossing_[a]);
    seg->t0 = tMin_;
    seg->t1 = tExit;
    seg->sigmaMaj = scalar_ ? scale_ * scalar_[cellIndex_] : scale_ * spectral_[cellIndex_];
    tMin_ = tExit;
    if (nextCrossing_[a] >= tMax_) {
        tMin_ = tMax_;
    } else {
        cell_[a] += step_[a];
        cellIndex_ += size_t(indexStep_[a]);
        if (cell_[a] == stop_[a]) tMin_ = tMax_;
        nextCrossing_[a] += deltaT_[a];
    }
    return true;
}

Vec3 MediumBox::toUnit(Vec3 pWorld) const {
    const Vec3 pm = toMedium(pWorld), e = p1 - p0;
    return {(pm.x - p0.x) / e.x, (pm.y - p0.y) / e.y, (pm.z - p0.z) / e.z};
}

bool MediumBox::clip(Vec3 o, Vec3 d, float tMax, Vec3* oUnit, Vec3* dUnit, float* t0Out, float* t1Out) const {
    // Slabs in the medium's space: the parameter t is the same in both spaces (an affine map),
    // so the clipped interval is in the world ray's distances.
    const Vec3 om = toMedium(o), dm = mediumFromWorld.vector(d);
    float t0 = 0, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        const float inv = 1 / dm[a];
        float tn = (p0[a] - om[a]) * inv, tf = (p1[a] - om[a]) * inv;
        if (tn > tf) std::swap(tn, tf);
        if (std::isnan(tn) || std::isnan(tf)) {  // parallel to the slab and on its plane
            if (om[a] < p0[a] || om[a] > p1[a]) return false;
            continue;
        }
        t0 = std::max(t0, tn);
        t1 = std::min(t1, tf);
        if (t0 > t1) return false;
    }
    const Vec3 e = p1 - p0;
    *oUnit = Vec3{(om.x - p0.x) / e.x, (om.y - p0.y) / e.y, (om.z - p0.z) / e.z};
    *dUnit = Vec3{dm.x / e.x, dm.y / e.y, dm.z / e.z};
    *t0Out = t0;
    *t1Out = t1;
    return true;
}

}  // namespace ps
