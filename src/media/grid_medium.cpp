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

template <typename T>
template <typename R, typename F>
R VoxelGrid<T>::maxOver(Vec3 lo, Vec3 hi, F&& bound) const {
    // lookup blends the voxels floor(p n - 1/2) and the next along each axis; one voxel of
    // slack each way (pbrt-v4's "filter slop") covers points that rounding puts in a
    // neighbouring cell. Voxels outside the grid blend in as zero, below any bound.
    const int n[3] = {nx, ny, nz};
    int i0[3], i1[3];
    for (int a = 0; a < 3; ++a) {
        i0[a] = std::max(0, int(std::floor(lo[a] * n[a] - 0.5f)) - 1);
        i1[a] = std::min(n[a] - 1, int(std::floor(hi[a] * n[a] - 0.5f)) + 2);
    }
    R m{};
    for (int z = i0[2]; z <= i1[2]; ++z)
        for (int y = i0[1]; y <= i1[1]; ++y)
            for (int x = i0[0]; x <= i1[0]; ++x) m = bound(m, values[(size_t(z) * ny + y) * nx + x]);
    return m;
}

GridMedium::GridMedium(const Box& box, VoxelGrid<float> density, MediumSpectrum sigmaA, MediumSpectrum sigmaS,
                       MediumSpectrum Le, VoxelGrid<float> LeScale, float g)
    : Medium(g), box_(box), density_(std::move(density)), LeScale_(std::move(LeScale)), sigmaA_(std::move(sigmaA)),
      sigmaS_(std::move(sigmaS)), Le_(std::move(Le)) {
    majorants_.fill([&](Vec3 lo, Vec3 hi) {
        return Spectrum(density_.maxOver<float>(lo, hi, [](float m, float v) { return std::max(m, v); }));
    });
    float maxLe = 0;
    for (float v : LeScale_.values) maxLe = std::max(maxLe, v);
    emissive_ = Le_.maxValue() > 0 && maxLe > 0;
}

GridMedium::GridMedium(const Box& box, VoxelGrid<Spectrum> sigmaA, VoxelGrid<Spectrum> sigmaS, const RGBColorSpace* space,
                       float g, VoxelGrid<Spectrum> Le, float LeScale)
    : Medium(g), box_(box), rgb_(true), rgbA_(std::move(sigmaA)), rgbS_(std::move(sigmaS)), rgbLe_(std::move(Le)),
      rgbLeScale_(LeScale), space_(space ? space : &srgbColorSpace()), liftedMajorants_(16, 16, 16) {
    // pbrt-v4's RGBGridMedium emits when it has an Le grid and Lescale > 0.
    float maxLe = 0;
    for (const Spectrum& v : rgbLe_.values) maxLe = std::max(maxLe, v.maxComponent());
    emissive_ = maxLe > 0 && rgbLeScale_ > 0;
    // Per channel in RGB mode; in spectral mode an unbounded lift scale * sigmoid(...) never
    // exceeds its scale, 2 max(rgb). A missing grid is 1 everywhere (pbrt-v4's default).
    auto perChannel = [](const Spectrum& m, const Spectrum& v) {
        return Spectrum(std::max(m.r, v.r), std::max(m.g, v.g), std::max(m.b, v.b));
    };
    auto lifted = [](const Spectrum& m, const Spectrum& v) { return Spectrum(std::max(m.r, 2 * v.maxComponent())); };
    auto cell = [&](Vec3 lo, Vec3 hi, auto&& bound) {
        auto of = [&](const VoxelGrid<Spectrum>& grid) {
            return grid.values.empty() ? Spectrum(1.0f) : grid.maxOver<Spectrum>(lo, hi, bound);
        };
        return of(rgbA_) + of(rgbS_);
    };
    majorants_.fill([&](Vec3 lo, Vec3 hi) { return cell(lo, hi, perChannel); });
    liftedMajorants_.fill([&](Vec3 lo, Vec3 hi) { return cell(lo, hi, lifted); });
}

MediumProperties GridMedium::at(Vec3 p, const SampledWavelengths* lambda) const {
    const Vec3 u = box_.toUnit(p);
    if (!rgb_) {
        auto same = [](float v) { return v; };
        const float d = density_.lookup(u, same);
        MediumProperties mp{sigmaA_(lambda) * d, sigmaS_(lambda) * d, Spectrum(0.0f)};
        if (emissive_) mp.Le = Le_(lambda) * LeScale_.lookup(u, same);
        return mp;
    }
    auto lift = [&](const Spectrum& rgb) { return lambda ? liftUnbounded(rgb, *lambda, *space_) : rgb; };
    auto grid = [&](const VoxelGrid<Spectrum>& g) { return g.values.empty() ? Spectrum(1.0f) : g.lookup(u, lift); };
    MediumProperties mp{grid(rgbA_), grid(rgbS_), Spectrum(0.0f)};
    if (emissive_) {
        // Each voxel's RGB is an illuminant of the colour space (pbrt-v4's RGBIlluminantSpectrum),
        // the lifted spectra blended as the sigma grids' are; RGB mode takes the colour itself.
        auto illuminant = [&](const Spectrum& rgb) {
            return lambda ? liftIlluminant(rgb, *lambda, *space_) : toRenderingSpace(rgb, space_, SpectrumKind::Illuminant);
        };
        mp.Le = rgbLe_.lookup(u, illuminant) * rgbLeScale_;
    }
    return mp;
}

MajorantIterator GridMedium::majorants(Vec3 o, Vec3 d, float tMax, const SampledWavelengths* lambda) const {
    if (!rgb_) return box_.iterate(o, d, tMax, majorants_, sigmaA_(lambda) + sigmaS_(lambda));
    return box_.iterate(o, d, tMax, majorantGrid(lambda != nullptr), Spectrum(1.0f));
}

}  // namespace ps
