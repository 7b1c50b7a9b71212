// Helpers of the media tests (media_render_test.cpp, heterogeneous_media_test.cpp,
// nanovdb_test.cpp): sample means, a scene whose camera sits in a medium, ratio-tracked
// transmittance between two points, and the first located error of a scene.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "media/majorant_grid.h"
#include "media/transmittance.h"
#include "render/scene_builder.h"
#include "scene/parser.h"
#include "util/error.h"

namespace ps::test {

// Mean and standard error of n draws.
struct Mean {
    double mean = 0, se = 0;
};
template <class F>
Mean meanOf(int n, F&& draw) {
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        const double x = draw();
        s += x;
        s2 += x * x;
    }
    Mean m;
    m.mean = s / n;
    m.se = std::sqrt(std::max(0.0, s2 / n - m.mean * m.mean) / (n - 1));
    return m;
}

// A scene whose camera is in `medium` (pbrt-v4's CameraMedium), to reach the medium.
inline std::unique_ptr<Scene> sceneInMedium(const std::string& medium, bool spectral = false) {
    setWarningsQuiet(true);
    const std::string text = "MakeNamedMedium \"m\" " + medium + R"(
        MediumInterface "" "m"
        Camera "perspective"
        WorldBegin
    )";
    return buildScene(parseSceneString(text, ".", "<test>"), spectral);
}

// The camera inside an emitting sphere of radiance 1 whose surface is black, all of it filled
// with `medium`: whatever the medium scatters, every path ends on the wall or in absorption,
// and where it absorbs it also emits Le = 1 (sigma_a Le), so the radiance is 1 everywhere
// (with the depth limit far beyond what the paths reach: 200 by default).
inline std::string enclosedFurnace(const std::string& medium, const std::string& integrator = "volpath", int maxDepth = 200) {
    return "MakeNamedMedium \"fog\" " + medium + R"(
        MediumInterface "" "fog"
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "perspective" "float fov" [ 70 ]
        Film "rgb" "integer xresolution" [ 12 ] "integer yresolution" [ 12 ]
        Sampler "independent"
        Integrator ")" + integrator + R"(" "integer maxdepth" [ )" + std::to_string(maxDepth) + R"( ]
        WorldBegin
        AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
        Material "diffuse" "rgb reflectance" [ 0 0 0 ]
        ReverseOrientation
        Shape "sphere" "float radius" [ 1 ]
    )";
}

// Ratio tracking from p0 to p1, per channel in RGB mode with the hero drawn uniformly as the
// path tracer draws it: the estimate of each channel's transmittance is T / mean(rL), what a
// shadow ray towards a delta light contributes (media/transmittance.h).
inline std::array<Mean, 3> ratioTracked(const Scene& scene, Vec3 p0, Vec3 p1, int n) {
    std::array<Mean, 3> out;
    Rng rng(11);
    for (int c = 0; c < 3; ++c) {
        Rng local(17 + c);
        out[c] = meanOf(n, [&] {
            const int hero = std::min(2, int(local.uniform() * 3));
            TransmittanceEstimate e = transmittance(scene, p0, Vec3(0, 0, 0), scene.cameraMedium(), p1, 0, nullptr, hero, false, rng);
            return e.T.isBlack() ? 0.0 : double(e.T[c] / channelMean(e.rL, false));
        });
    }
    return out;
}

inline void expectTransmittance(const std::array<Mean, 3>& got, const std::array<double, 3>& exact, const char* what) {
    for (int c = 0; c < 3; ++c) {
        std::printf("  %s channel %d: %.5f +- %.5f, exp(-tau) %.5f, %+.2f sigma\n", what, c, got[c].mean, got[c].se, exact[c],
                    (got[c].mean - exact[c]) / got[c].se);
        EXPECT_NEAR(got[c].mean, exact[c], 4 * got[c].se) << what << " channel " << c;
        EXPECT_LT(4 * got[c].se, 0.02 * exact[c]) << what << ": cannot resolve a 2% error";
    }
}

// An orthographic view (16 x 16 pixels) through two quads at z = 1 and 2.5, normals outwards
// (away from the 1.5 between them), onto a black light of radiance 1 behind them that covers
// the view (reflecting, it would add light the quads reflect back to it); `header` comes before WorldBegin, `attributes` (material, media) before the quads.
inline std::string slabScene(const std::string& header, const std::string& attributes) {
    return R"(
        LookAt 0 0 0  0 0 1  0 1 0
        Camera "orthographic"
        Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ]
        Sampler "independent"
        )" + header + R"(
        WorldBegin
        AttributeBegin
          )" + attributes + R"(
          Shape "trianglemesh" "point3 P" [ -5 -5 1  5 -5 1  5 5 1  -5 5 1 ] "integer indices" [ 0 1 2  0 2 3 ]
              "normal N" [ 0 0 -1  0 0 -1  0 0 -1  0 0 -1 ]
          Shape "trianglemesh" "point3 P" [ -5 -5 2.5  5 -5 2.5  5 5 2.5  -5 5 2.5 ] "integer indices" [ 0 1 2  0 2 3 ]
              "normal N" [ 0 0 1  0 0 1  0 0 1  0 0 1 ]
        AttributeEnd
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
          Material "diffuse" "rgb reflectance" [ 0 0 0 ]
          ReverseOrientation
          Shape "disk" "float height" [ 3 ] "float radius" [ 10 ]
        AttributeEnd
    )";
}

// The message of the InputError that building `text` (named scene.pbrt) raises, or "".
inline std::string buildError(const std::string& text) {
    setWarningsQuiet(true);
    try {
        buildScene(parseSceneString(text, ".", "scene.pbrt"), false);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// The number of random points of a majorant grid's cells (unit coordinates, mapped to the
// world by `toWorld`) where `density` exceeds the cell's bound in some channel.
template <typename T, typename Density, typename ToWorld>
inline int countCellViolations(const MajorantGridOf<T>& grid, int perCell, Density&& density, ToWorld&& toWorld) {
    Rng rng(7);
    int bad = 0;
    for (int z = 0; z < grid.res[2]; ++z)
        for (int y = 0; y < grid.res[1]; ++y)
            for (int x = 0; x < grid.res[0]; ++x) {
                const Vec3 lo = grid.cellMin(x, y, z), hi = grid.cellMax(x, y, z);
                for (int i = 0; i < perCell; ++i) {
                    // Corners and faces too: there the neighbouring cells' values blend in.
                    auto coord = [&](float a, float b) {
                        const float u = rng.uniform();
                        return i < 8 ? (u < 0.5f ? a : b) : a + (b - a) * u;
                    };
                    const Vec3 u(coord(lo.x, hi.x), coord(lo.y, hi.y), coord(lo.z, hi.z));
                    const Spectrum d = density(toWorld(u)), m = Spectrum(grid.at(x, y, z));
                    for (int c = 0; c < 4; ++c)
                        if (d[c] > m[c] * (1 + 1e-5f) + 1e-6f) {
                            if (bad++ < 5)
                                ADD_FAILURE() << "cell (" << x << "," << y << "," << z << ") channel " << c << ": density " << d[c]
                                              << " > majorant " << m[c];
                        }
                }
            }
    return bad;
}

// tau along a to b by a midpoint rule of `steps`, counting only points inside the medium's
// box (tracking never leaves it; trilinear lookups just outside it are not zero).
template <typename Inside>
inline std::array<double, 3> opticalDepth(const Medium& medium, Vec3 a, Vec3 b, int steps, Inside&& inside) {
    std::array<double, 3> tau{0, 0, 0};
    const Vec3 d = b - a;
    for (int i = 0; i < steps; ++i) {
        const Vec3 p = a + d * ((i + 0.5f) / steps);
        if (!inside(p)) continue;
        const MediumProperties mp = medium.at(p, nullptr);
        for (int c = 0; c < 3; ++c) tau[c] += (mp.sigmaA[c] + mp.sigmaS[c]) * length(d) / steps;
    }
    return tau;
}

}  // namespace ps::test
