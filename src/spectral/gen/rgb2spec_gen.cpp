// Build-time generator of the RGB-to-spectrum coefficient tables (Jakob & Hanika 2019, "A
// Low-Dimensional Function Space for Efficient Spectral Upsampling"): for every table node
// it finds the sigmoid polynomial s(lambda) = S(c0 t^2 + c1 t + c2), t = (lambda - 360)/470,
// whose colour under the space's illuminant is the node's RGB, by Gauss-Newton on the CIELAB
// difference. Colours are the sums over the same 1 nm grid the renderer's film uses, so the
// tables reproduce RGB as the renderer measures it.
//
// Usage: rgb2spec_gen OUT_DIR   writes OUT_DIR/rgb2spec_<space>.bin for the four named
// spaces (raw native floats, layout in rgb_table_layout.h) and OUT_DIR/rgb2spec_tables.h
// (a checksum per table, so that object files embedding them change with the data).
#include "spectral/cie.h"
#include "spectral/colorimetry.h"
#include "spectral/rgb_color_space.h"
#include "spectral/rgb_table_layout.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace ps {
namespace {

using Vec = std::array<double, 3>;

// Everything the optimiser needs for one colour space.
struct Problem {
    double t[kCieSamples];            // normalised wavelength of each grid point
    double weight[3][kCieSamples];    // RGB contribution of reflectance 1 at each grid point
    Matrix3 xyzFromRGB;
    Vec whiteXYZ;                     // XYZ of RGB (1,1,1), the CIELAB reference white

    explicit Problem(const RGBColorSpace& space) {
        const Colorimetry& c = colorimetry(space);
        xyzFromRGB = c.xyzFromRGB;
        whiteXYZ = xyzFromRGB * Vec{1, 1, 1};
        double yIllum = 0;
        for (int i = 0; i < kCieSamples; ++i) yIllum += double(kCieY[i]) * c.illuminant.value[i];
        for (int i = 0; i < kCieSamples; ++i) {
            t[i] = double(i) / (kCieSamples - 1);
            const Vec cmf{kCieX[i], kCieY[i], kCieZ[i]};
            const Vec rgb = c.rgbFromXYZ * cmf;
            for (int ch = 0; ch < 3; ++ch) weight[ch][i] = rgb[size_t(ch)] * c.illuminant.value[i] / yIllum;
        }
    }

    static double labF(double v) {
        constexpr double d = 6.0 / 29.0;
        return v > d * d * d ? std::cbrt(v) : v / (3 * d * d) + 4.0 / 29.0;
    }
    static double labFPrime(double v) {
        constexpr double d = 6.0 / 29.0;
        return v > d * d * d ? 1.0 / (3 * std::cbrt(v * v)) : 1.0 / (3 * d * d);
    }

    Vec lab(const Vec& rgb) const {
        const Vec xyz = xyzFromRGB * rgb;
        const double fx = labF(xyz[0] / whiteXYZ[0]), fy = labF(xyz[1] / whiteXYZ[1]), fz = labF(xyz[2] / whiteXYZ[2]);
        return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
    }

    // Lab of the coefficients' spectrum and its Jacobian d Lab / d c.
    Vec labAndJacobian(const Vec& c, double jac[3][3]) const {
        Vec rgb{0, 0, 0};
        double drgb[3][3] = {};  // [channel][coefficient]
        for (int i = 0; i < kCieSamples; ++i) {
            const double ti = t[i];
            const double x = (c[0] * ti + c[1]) * ti + c[2];
            const double q = 1 / std::sqrt(1 + x * x);
            const double s = 0.5 + 0.5 * x * q;
            const double ds = 0.5 * q * q * q;
            const double dc[3] = {ds * ti * ti, ds * ti, ds};
            for (int ch = 0; ch < 3; ++ch) {
                const double w = weight[ch][i];
                rgb[size_t(ch)] += w * s;
                for (int k = 0; k < 3; ++k) drgb[ch][k] += w * dc[k];
            }
        }
        const Vec xyz = xyzFromRGB * rgb;
        double dxyz[3][3] = {};
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k)
                for (int ch = 0; ch < 3; ++ch) dxyz[r][k] += xyzFromRGB.a[r][ch] * drgb[ch][k];
        double f[3], fp[3];
        for (int r = 0; r < 3; ++r) {
            const double v = xyz[size_t(r)] / whiteXYZ[size_t(r)];
            f[r] = labF(v);
            fp[r] = labFPrime(v) / whiteXYZ[size_t(r)];
        }
        for (int k = 0; k < 3; ++k) {
            const double dfx = fp[0] * dxyz[0][k], dfy = fp[1] * dxyz[1][k], dfz = fp[2] * dxyz[2][k];
            jac[0][k] = 116 * dfy;
            jac[1][k] = 500 * (dfx - dfy);
            jac[2][k] = 200 * (dfy - dfz);
        }
        return {116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])};
    }

    static double norm2(const Vec& r) { return r[0] * r[0] + r[1] * r[1] + r[2] * r[2]; }

    // Gauss-Newton from `c` towards the target Lab; a step that does not reduce the error is
    // halved (the sigmoid saturates, so full steps can overshoot for saturated colours).
    void solve(const Vec& targetLab, Vec& c) const {
        double jac[3][3];
        Vec cur = labAndJacobian(c, jac);
        Vec res{targetLab[0] - cur[0], targetLab[1] - cur[1], targetLab[2] - cur[2]};
        double err = norm2(res);
        for (int it = 0; it < 30 && err > 1e-8; ++it) {
            Matrix3 j;
            for (int r = 0; r < 3; ++r)
                for (int k = 0; k < 3; ++k) j.a[r][k] = jac[r][k];
            if (!(std::fabs(j.determinant()) > 1e-30)) break;
            const Vec step = j.inverse() * res;
            bool improved = false;
            for (double scale = 1; scale > 1.0 / 64; scale *= 0.5) {
                Vec trial{c[0] + scale * step[0], c[1] + scale * step[1], c[2] + scale * step[2]};
                // Keep the polynomial bounded as pbrt-v4 does (it rescales when the largest
                // coefficient passes 200), so that saturated colours end in a steep but
                // finite sigmoid rather than running off.
                const double m = std::max({trial[0], trial[1], trial[2]});
                if (m > 200)
                    for (double& v : trial) v *= 200 / m;
                double tjac[3][3];
                const Vec tl = labAndJacobian(trial, tjac);
                const Vec tres{targetLab[0] - tl[0], targetLab[1] - tl[1], targetLab[2] - tl[2]};
                const double terr = norm2(tres);
                if (terr < err) {
                    c = trial;
                    res = tres;
                    err = terr;
                    std::copy(&tjac[0][0], &tjac[0][0] + 9, &jac[0][0]);
                    improved = true;
                    break;
                }
            }
            if (!improved) break;
        }
    }
};

// Coefficients in t = (lambda - 360)/470 rewritten as a polynomial in lambda (nm).
void toNanometres(const Vec& c, float* out) {
    const double a = 1.0 / (kCieLambdaMax - kCieLambdaMin), o = kCieLambdaMin;
    out[0] = float(c[0] * a * a);
    out[1] = float(c[1] * a - 2 * c[0] * o * a * a);
    out[2] = float(c[2] - c[1] * o * a + c[0] * o * o * a * a);
}

// One (max component, y) row of the table: for each x, the brightness nodes are solved in
// order from res/5 upwards and then downwards, each warm-started from its neighbour.
void solveRow(const Problem& p, int m, int j, std::vector<float>& table) {
    const double y = double(j) / (kRgbTableRes - 1);
    const int start = kRgbTableRes / 5;
    for (int i = 0; i < kRgbTableRes; ++i) {
        const double x = double(i) / (kRgbTableRes - 1);
        auto solveAt = [&](int k, Vec& c) {
            const double z = rgbTableBrightness(k);
            Vec rgb;
            rgb[size_t(m)] = z;
            rgb[size_t((m + 1) % 3)] = x * z;
            rgb[size_t((m + 2) % 3)] = y * z;
            p.solve(p.lab(rgb), c);
            toNanometres(c, &table[rgbTableIndex(m, k, j, i)]);
        };
        Vec c{0, 0, 0};
        solveAt(start, c);
        const Vec atStart = c;
        for (int k = start + 1; k < kRgbTableRes; ++k) solveAt(k, c);
        c = atStart;
        for (int k = start - 1; k >= 0; --k) solveAt(k, c);
    }
}

uint64_t fnv1a(const void* data, size_t n) {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

}  // namespace
}  // namespace ps

int main(int argc, char** argv) {
    using namespace ps;
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Problem> problems;
    for (int s = 0; s < kNamedColorSpaces; ++s) problems.emplace_back(colorSpaceByIndex(s));
    std::vector<std::vector<float>> tables(kNamedColorSpaces, std::vector<float>(kRgbTableFloats));

    // Rows of all tables share one work queue; each row is independent, so the result does
    // not depend on the thread count.
    const int rowsPerTable = 3 * kRgbTableRes, rows = kNamedColorSpaces * rowsPerTable;
    std::atomic<int> next{0};
    auto worker = [&] {
        for (int r; (r = next.fetch_add(1)) < rows;) {
            const int s = r / rowsPerTable, m = (r % rowsPerTable) / kRgbTableRes, j = r % kRgbTableRes;
            solveRow(problems[size_t(s)], m, j, tables[size_t(s)]);
        }
    };
    const unsigned n = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> threads;
    for (unsigned i = 1; i < n; ++i) threads.emplace_back(worker);
    worker();
    for (auto& t : threads) t.join();

    std::string header = "// Generated by rgb2spec_gen: checksums of the embedded tables.\n#pragma once\n";
    for (int s = 0; s < kNamedColorSpaces; ++s) {
        const std::string name = colorSpaceByIndex(s).name;
        const std::string path = dir + "/rgb2spec_" + name + ".bin";
        FILE* f = std::fopen(path.c_str(), "wb");
        const std::vector<float>& t = tables[size_t(s)];
        if (!f || std::fwrite(t.data(), sizeof(float), t.size(), f) != t.size() || std::fclose(f) != 0) {
            std::fprintf(stderr, "rgb2spec_gen: cannot write %s\n", path.c_str());
            return 1;
        }
        char line[128];
        std::snprintf(line, sizeof line, "#define PS_RGB2SPEC_CHECKSUM_%d 0x%016llxull\n", s,
                      (unsigned long long)fnv1a(t.data(), t.size() * sizeof(float)));
        header += line;
    }
    const std::string hpath = dir + "/rgb2spec_tables.h";
    FILE* h = std::fopen(hpath.c_str(), "wb");
    if (!h || std::fputs(header.c_str(), h) < 0 || std::fclose(h) != 0) {
        std::fprintf(stderr, "rgb2spec_gen: cannot write %s\n", hpath.c_str());
        return 1;
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("rgb2spec_gen: %d tables in %.1f s on %u threads\n", kNamedColorSpaces, secs, n);
    return 0;
}
