// pbrt-v4's MajorantGrid and DDAMajorantIterator (media.h): a coarse grid over a medium's box
// whose cells hold a bound on the density inside them, and the walk of a ray through its cells
// in order (Amanatides and Woo's 3D DDA). Delta and ratio tracking then sample each cell's part
// of the ray against that cell's bound, so that a sparse or peaky medium takes long steps where
// it is thin instead of the whole box's largest density everywhere. Shared by the grid, cloud
// and nanovdb media; the homogeneous medium keeps its single segment.
#pragma once
#include <type_traits>
#include <vector>
#include "math/transform.h"
#include "media/medium.h"

namespace ps {

// T is float for media whose sigma_t is a density times one spectrum (one bound per cell,
// times the iterator's scale: a quarter of the memory of a Spectrum per cell), Spectrum for
// rgbgrid's per-channel bounds.
template <typename T>
struct MajorantGridOf {
    int res[3] = {1, 1, 1};
    std::vector<T> cells;  // x fastest; multiplied by the iterator's scale

    MajorantGridOf() = default;
    MajorantGridOf(int nx, int ny, int nz) : res{nx, ny, nz}, cells(size_t(nx) * ny * nz, T(0.0f)) {}
    T& at(int x, int y, int z) { return cells[(size_t(z) * res[1] + y) * res[0] + x]; }
    const T& at(int x, int y, int z) const { return cells[(size_t(z) * res[1] + y) * res[0] + x]; }
    // Cell (x, y, z)'s corners in the box's unit coordinates [0,1]^3.
    Vec3 cellMin(int x, int y, int z) const { return {float(x) / res[0], float(y) / res[1], float(z) / res[2]}; }
    Vec3 cellMax(int x, int y, int z) const { return {float(x + 1) / res[0], float(y + 1) / res[1], float(z + 1) / res[2]}; }
    // Fills every cell with bound(cellMin, cellMax) in parallel.
    template <typename F>
    void fill(F&& bound);
};
using MajorantGrid = MajorantGridOf<float>;
using SpectralMajorantGrid = MajorantGridOf<Spectrum>;

// The segments of a ray, in world distances along its unit direction, each with its majorant.
// Either one segment (homogeneous media) or a walk through a MajorantGrid's cells.
class MajorantIterator {
public:
    MajorantIterator() = default;  // no segment: the ray misses the medium
    MajorantIterator(float t0, float t1, const Spectrum& sigmaMaj) : tMin_(t0), tMax_(t1), scale_(sigmaMaj) {}
    // oUnit + t dUnit is the ray in the grid's unit coordinates; t in [t0, t1] lies in the box.
    template <typename T>
    MajorantIterator(const MajorantGridOf<T>* grid, Vec3 oUnit, Vec3 dUnit, float t0, float t1, const Spectrum& scale)
        : MajorantIterator(grid->res, oUnit, dUnit, t0, t1, scale) {
        if constexpr (std::is_same_v<T, float>) scalar_ = grid->cells.data();
        else spectral_ = grid->cells.data();
    }

    bool next(MajorantSegment* seg);

private:
    MajorantIterator(const int res[3], Vec3 oUnit, Vec3 dUnit, float t0, float t1, const Spectrum& scale);

    const float* scalar_ = nullptr;  // one of the two: the cells, or neither (one segment)
    const Spectrum* spectral_ = nullptr;
    size_t cellIndex_ = 0;            // of cell_ in the cells, moved by indexStep_
    float tMin_ = 0, tMax_ = 0;  // tMin_ >= tMax_: finished
    Spectrum scale_;
    float nextCrossing_[3] = {}, deltaT_[3] = {};
    int cell_[3] = {}, step_[3] = {}, stop_[3] = {};
    ptrdiff_t indexStep_[3] = {};
};

// A medium's box p0..p1 in its own space, placed in the world by the CTM at MakeNamedMedium.
struct MediumBox {
    Transform mediumFromWorld;
    Vec3 p0{0, 0, 0}, p1{1, 1, 1};

    Vec3 toMedium(Vec3 pWorld) const { return mediumFromWorld.point(pWorld); }
    Vec3 toUnit(Vec3 pWorld) const;
    // The part of o + t d (world, d unit, t in [0, tMax]) inside the box, walking `grid`'s cells
    // with their values times `scale`; an empty iterator when the box is missed.
    template <typename T>
    MajorantIterator iterate(Vec3 o, Vec3 d, float tMax, const MajorantGridOf<T>& grid, const Spectrum& scale) const {
        Vec3 oUnit, dUnit;
        float t0, t1;
        if (!clip(o, d, tMax, &oUnit, &dUnit, &t0, &t1)) return {};
        return MajorantIterator(&grid, oUnit, dUnit, t0, t1, scale);
    }
    // The part [t0, t1] of the ray inside the box and the ray in unit coordinates; false when missed.
    bool clip(Vec3 o, Vec3 d, float tMax, Vec3* oUnit, Vec3* dUnit, float* t0, float* t1) const;
};

}  // namespace ps

#include <tbb/parallel_for.h>

template <typename T>
template <typename F>
void ps::MajorantGridOf<T>::fill(F&& bound) {
    tbb::parallel_for(0, res[2], [&](int z) {
        for (int y = 0; y < res[1]; ++y)
            for (int x = 0; x < res[0]; ++x) at(x, y, z) = bound(cellMin(x, y, z), cellMax(x, y, z));
    });
}
