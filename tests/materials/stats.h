// Statistical helpers for the BxDF tests: a Monte Carlo furnace estimate with its standard
// error, Pearson's chi-square test of sampled directions against a density on a (theta,
// phi) grid, and quadrature of densities over the sphere.
#pragma once
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "materials/bxdf.h"
#include "mc/rng.h"

namespace ps::test {

struct MeanSE {
    double mean = 0, se = 0;
};

// Mean and standard error of n values produced by next().
inline MeanSE meanAndError(int n, const std::function<double()>& next) {
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        double v = next();
        sum += v;
        sum2 += v * v;
    }
    double mean = sum / n;
    double var = std::max(0.0, sum2 / n - mean * mean) * n / std::max(1, n - 1);
    return {mean, std::sqrt(var / n)};
}

// Directional albedo of b for wo by importance sampling: E[f |cos wi| / pdf] (green channel).
inline MeanSE furnace(const BxDF& b, Vec3 wo, TransportMode mode, int n, uint64_t seed) {
    Rng rng(seed);
    return meanAndError(n, [&] {
        float uc = rng.uniform();
        Vec2 u(rng.uniform(), rng.uniform());
        auto s = b.sample(wo, uc, u, mode);
        if (!s || !(s->pdf > 0)) return 0.0;
        return double(s->f.g) * std::fabs(s->wi.z) / s->pdf;
    });
}

// Regularised upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a): the series
// for P below x = a + 1, Lentz's continued fraction for Q above.
inline double gammaQ(double a, double x) {
    if (x <= 0) return 1;
    double lnPre = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1) {
        double term = 1 / a, sum = term;
        for (int n = 1; n < 100000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
        }
        return std::max(0.0, 1 - sum * std::exp(lnPre));
    }
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1 / d;
        double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1) < 1e-15) break;
    }
    return std::exp(lnPre) * h;
}

// P(chi^2_dof >= x).
inline double chiSquarePValue(double x, int dof) { return gammaQ(dof / 2.0, x / 2.0); }

// Per-test significance so that the family of `tests` tests rejects a correct sampler with
// probability `alpha` overall (Sidak correction).
inline double sidak(double alpha, int tests) { return 1 - std::pow(1 - alpha, 1.0 / tests); }

// Pearson's statistic after pooling cells whose expected count is below 5 (the pooled
// cells form one cell); returns {chi2, p-value}.
struct ChiSquareResult {
    double chi2 = 0, pValue = 1;
    int dof = 0;
};
// When the expected counts are themselves Monte Carlo estimates, expectedVar holds their
// variances: O - E then has variance E + Var(E), which replaces E in the denominator.
inline ChiSquareResult chiSquare(const std::vector<double>& observed, const std::vector<double>& expected,
                                 const std::vector<double>& expectedVar = {}) {
    ChiSquareResult r;
    double pooledE = 0, pooledO = 0, pooledV = 0;
    int cells = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        double v = expectedVar.empty() ? 0.0 : expectedVar[i];
        if (expected[i] < 5) {
            pooledE += expected[i];
            pooledO += observed[i];
            pooledV += v;
            continue;
        }
        r.chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / (expected[i] + v);
        ++cells;
    }
    if (pooledE > 0) {
        // Too small a pooled cell says little; anything observed where nothing is expected
        // is still a failure.
        if (pooledE >= 5) {
            r.chi2 += (pooledO - pooledE) * (pooledO - pooledE) / (pooledE + pooledV);
            ++cells;
        } else if (pooledO > pooledE + 10 + 5 * std::sqrt(pooledE)) {
            r.chi2 += 1e9;
        }
    }
    r.dof = std::max(1, cells - 1);
    r.pValue = chiSquarePValue(r.chi2, r.dof);
    return r;
}

// A (theta, phi) grid over the whole sphere, theta in [0, pi] from +z.
struct SphereGrid {
    int nTheta, nPhi;
    SphereGrid(int nt, int np) : nTheta(nt), nPhi(np) {}
    int cells() const { return nTheta * nPhi; }
    int cellOf(Vec3 w) const {
        float theta = std::acos(std::clamp(w.z, -1.0f, 1.0f));
        float phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * kPi;
        int t = std::min(nTheta - 1, int(theta / kPi * nTheta));
        int p = std::min(nPhi - 1, int(phi / (2 * kPi) * nPhi));
        return t * nPhi + p;
    }
    // Integral of density over each cell by the midpoint rule on sub x sub points (with the
    // sin(theta) Jacobian).
    std::vector<double> integrate(const std::function<double(Vec3)>& density, int sub) const {
        std::vector<double> out(cells(), 0.0);
        double dT = M_PI / nTheta, dP = 2 * M_PI / nPhi;
        for (int t = 0; t < nTheta; ++t)
            for (int p = 0; p < nPhi; ++p) {
                double acc = 0;
                for (int i = 0; i < sub; ++i)
                    for (int j = 0; j < sub; ++j) {
                        double theta = (t + (i + 0.5) / sub) * dT, phi = (p + (j + 0.5) / sub) * dP;
                        Vec3 w(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
                        acc += density(w) * std::sin(theta);
                    }
                out[t * nPhi + p] = acc * dT * dP / (sub * sub);
            }
        return out;
    }
};

// Integral of a density over the sphere.
inline double integrateSphere(const std::function<double(Vec3)>& density, int nTheta = 400, int nPhi = 400) {
    std::vector<double> cells = SphereGrid(nTheta, nPhi).integrate(density, 1);
    double s = 0;
    for (double c : cells) s += c;
    return s;
}

inline Vec3 directionAt(float cosTheta, float phi = 0.3f) {
    float s = std::sqrt(std::max(0.0f, 1 - cosTheta * cosTheta));
    return Vec3(s * std::cos(phi), s * std::sin(phi), cosTheta);
}

}  // namespace ps::test
