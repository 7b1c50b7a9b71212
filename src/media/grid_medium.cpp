#include "media/grid_medium.h"

#include <algorithm>
#include <cmath>
#include "scene/color_space.h"

namespace ps {

template <typename T>
template <typename F>
auto VoxelGrid<T>::lookup(Vec3 p, F&& convert) const -> decltype(convert(values[0])) {
    using R = decltype(convert(values[0]));
    const float sx = p.x * nx - 0.5f, sy = p.y * ny - 0.5f, sz = p.z * nz - 0.5f;
    const int ix = int(std::floor(sx)), iy = int(std::floor(sy)), iz = int(std::floor(sz));
    const float fx = sx - ix, fy = sy - iy, fz = sz - iz;
    auto at = [&](int x, int y, int z) -> R {
        if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) return R{};
        return convert(values[(size_t(z) * ny + y) * nx + x]);
    };
    auto lerpR = [](float t, const R& a, const R& b) { return a * (1 - t) + b * t; };
    R c00 = lerpR(fx, at(ix, iy, iz), at(ix + 1, iy, iz)), c10 = lerpR(fx, at(ix, iy + 1, iz), at(ix + 1, iy + 1, iz));
    R c01 = lerpR(fx, at(ix, iy, iz + 1), at(ix + 1, iy, iz + 1));
    R c11 = lerpR(fx, at(ix, iy + 1, iz + 1), at(ix + 1, iy + 1, iz + 1));
    return lerpR(fz, lerpR(fy, c00, c10), lerpR(fy, c01, c11));
}

GridMedium::GridMedium(const Box& box, VoxelGrid<float> density, MediumSpectrum sigmaA, MediumSpectrum sigmaS,
                       MediumSpectrum Le, VoxelGrid<float> LeScale, float g)
    : Medium(g), box_(box), mediumFromWorld_(box.worldFromMedium.inverse()), density_(std::move(density)),
      LeScale_(std::move(LeScale)), sigmaA_(std::move(sigmaA)), sigmaS_(std::move(sigmaS)), Le_(std::move(Le)) {
    for (float v : density_.values) maxDensity_ = std::max(maxDensity_, v);
    float maxLe = 0;
    for (float v : LeScale_.values) maxLe = std::max(maxLe, v);
    emissive_ = Le_.maxValue() > 0 && maxLe > 0;
}

GridMedium::GridMedium(const Box& box, VoxelGrid<Spectrum> sigmaA, VoxelGrid<Spectrum> sigmaS, const RGBColorSpace* space,
                       float g)
    : Medium(g), box_(box), mediumFromWorld_(box.worldFromMedium.inverse()), rgb_(true), rgbA_(std::move(sigmaA)),
      rgbS_(std::move(sigmaS)), space_(space ? space : &srgbColorSpace()) {
    // An unbounded lift scale * sigmoid(...) never exceeds its scale, 2 max(rgb).
    auto bounds = [](const VoxelGrid<Spectrum>& grid, Spectrum* perChannel, float* lifted) {
        if (grid.values.empty()) {
            *perChannel = Spectrum(1.0f);
            *lifted = 1;
            return;
        }
        for (const Spectrum& v : grid.values) {
            perChannel->r = std::max(perChannel->r, v.r);
            perChannel->g = std::max(perChannel->g, v.g);
            perChannel->b = std::max(perChannel->b, v.b);
            *lifted = std::max(*lifted, 2 * v.maxComponent());
        }
        perChannel->c3 = perChannel->g;
    };
    Spectrum a, s;
    float la = 0, ls = 0;
    bounds(rgbA_, &a, &la);
    bounds(rgbS_, &s, &ls);
    rgbMajorant_ = a + s;
    spectralMajorant_ = la + ls;
}

Vec3 GridMedium::toUnit(Vec3 pWorld) const {
    const Vec3 pm = mediumFromWorld_.point(pWorld), e = box_.p1 - box_.p0;
    return {(pm.x - box_.p0.x) / e.x, (pm.y - box_.p0.y) / e.y, (pm.z - box_.p0.z) / e.z};
}

MediumProperties GridMedium::at(Vec3 p, const SampledWavelengths* lambda) const {
    const Vec3 u = toUnit(p);
    if (!rgb_) {
        auto same = [](float v) { return v; };
        const float d = density_.lookup(u, same);
        MediumProperties mp{sigmaA_(lambda) * d, sigmaS_(lambda) * d, Spectrum(0.0f)};
        if (emissive_) mp.Le = Le_(lambda) * LeScale_.lookup(u, same);
        return mp;
    }
    auto lift = [&](const Spectrum& rgb) { return lambda ? liftUnbounded(rgb, *lambda, *space_) : rgb; };
    auto grid = [&](const VoxelGrid<Spectrum>& g) { return g.values.empty() ? Spectrum(1.0f) : g.lookup(u, lift); };
    return {grid(rgbA_), grid(rgbS_), Spectrum(0.0f)};
}

// The ray against the box p0..p1 in the medium's space (slabs); the parameter is the same in
// both spaces, so the segment is in the world ray's distances.
bool GridMedium::segment(Vec3 o, Vec3 d, float tMax, const SampledWavelengths* lambda, MajorantSegment* seg) const {
    const Vec3 om = mediumFromWorld_.point(o), dm = mediumFromWorld_.vector(d);
    float t0 = 0, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        const float inv = 1 / dm[a];
        float tn = (box_.p0[a] - om[a]) * inv, tf = (box_.p1[a] - om[a]) * inv;
        if (tn > tf) std::swap(tn, tf);
        if (std::isnan(tn) || std::isnan(tf)) {  // parallel to the slab and on its plane
            if (om[a] < box_.p0[a] || om[a] > box_.p1[a]) return false;
            continue;
        }
        t0 = std::max(t0, tn);
        t1 = std::min(t1, tf);
        if (t0 > t1) return false;
    }
    seg->t0 = t0;
    seg->t1 = t1;
    if (!rgb_) seg->sigmaMaj = (sigmaA_(lambda) + sigmaS_(lambda)) * maxDensity_;
    else seg->sigmaMaj = lambda ? Spectrum(spectralMajorant_) : rgbMajorant_;
    return true;
}

}  // namespace ps
