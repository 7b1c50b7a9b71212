#include "mc/test_integrands.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "mc/distribution.h"

namespace ps {

namespace {

// A density that is a product of one 1-D density per coordinate, each sampled by inversion.
struct Factor1D {
    std::function<double(double)> pdf;
    std::function<double(double)> sample;  // inverse CDF
};
ImportanceDensity productDensity(Factor1D factor) {
    ImportanceDensity d;
    d.pdf = [factor](std::span<const double> x) {
        double p = 1;
        for (double v : x) p *= factor.pdf(v);
        return p;
    };
    d.sample = [factor](std::span<const double> u, std::span<double> x) {
        for (size_t i = 0; i < u.size(); ++i) x[i] = factor.sample(u[i]);
    };
    return d;
}

// prod_i g(u_i) with integral G per coordinate.
void makeSeparable(TestIntegrand& t, std::function<double(double)> g, double G) {
    t.f = [g](std::span<const double> u) {
        double p = 1;
        for (double v : u) p *= g(v);
        return p;
    };
    t.exact = std::pow(G, t.dims);
    t.partial = [g, G](std::span<const double> u) {
        double p = G;
        for (double v : u) p *= g(v);
        return p;
    };
}

TestIntegrand makeExp(int dims) {
    TestIntegrand t{"exp", "prod e^u_i (smooth, monotone)", dims, {}, 0, {}, {}};
    makeSeparable(t, [](double u) { return std::exp(u); }, std::numbers::e - 1.0);
    // p(u) = (1 + u) / 1.5, the linear part of e^u; inverse CDF of (u + u^2/2) / 1.5.
    t.importance = productDensity({[](double u) { return (1.0 + u) / 1.5; },
                                   [](double xi) { return std::sqrt(1.0 + 3.0 * xi) - 1.0; }});
    return t;
}

TestIntegrand makeGaussian(int dims) {
    constexpr double c = 2.0;
    TestIntegrand t{"gaussian", "prod exp(-4 (u_i-1/2)^2) (smooth, symmetric peak)", dims, {}, 0, {}, {}};
    auto g = [](double u) { return std::exp(-c * c * (u - 0.5) * (u - 0.5)); };
    makeSeparable(t, g, std::sqrt(std::numbers::pi) / c * std::erf(c / 2));
    // Reuse the tabulated inversion sampler (distribution.h) on 64 bins of the factor.
    std::vector<float> w(64);
    for (size_t i = 0; i < w.size(); ++i) w[i] = float(g((i + 0.5) / w.size()));
    auto table = std::make_shared<Distribution1D>(w);
    t.importance = productDensity({[table](double u) { return double(table->pdf(float(u))); },
                                   [table](double xi) {
                                       float pdf;
                                       return double(table->sampleContinuous(float(xi), &pdf));
                                   }});
    return t;
}

// P(U_1 + ... + U_s <= x), the Irwin-Hall distribution function.
double irwinHallCdf(double x, int s) {
    double sum = 0, binom = 1, fact = 1;
    for (int i = 2; i <= s; ++i) fact *= i;
    for (int k = 0; k <= s && k < x; ++k) {
        sum += (k % 2 ? -1.0 : 1.0) * binom * std::pow(x - k, s);
        binom = binom * (s - k) / (k + 1);
    }
    return sum / fact;
}

TestIntegrand makeHalfspace(int dims) {
    const double t0 = 0.4 * dims;
    TestIntegrand t{"halfspace", "1[sum u_i < 0.4 s] (discontinuous)", dims, {}, irwinHallCdf(t0, dims), {}, {}};
    t.f = [t0](std::span<const double> u) {
        double s = 0;
        for (double v : u) s += v;
        return s < t0 ? 1.0 : 0.0;
    };
    // Over the last coordinate: the length of {x in [0,1): sum' + x < t0}.
    t.partial = [t0](std::span<const double> u) {
        double s = 0;
        for (double v : u) s += v;
        return std::clamp(t0 - s, 0.0, 1.0);
    };
    return t;
}

TestIntegrand makeBall(int dims) {
    constexpr double r = 0.45;
    // Volume of the s-ball: pi^{s/2} r^s / Gamma(s/2 + 1).
    double exact = std::pow(std::numbers::pi, dims / 2.0) * std::pow(r, dims) / std::tgamma(dims / 2.0 + 1.0);
    TestIntegrand t{"ball", "1[|u - 1/2| < 0.45] (discontinuous, curved)", dims, {}, exact, {}, {}};
    t.f = [](std::span<const double> u) {
        double d2 = 0;
        for (double v : u) d2 += (v - 0.5) * (v - 0.5);
        return d2 < r * r ? 1.0 : 0.0;
    };
    // The chord through the ball along the last axis (it stays inside [0,1) as r < 1/2).
    t.partial = [](std::span<const double> u) {
        double d2 = 0;
        for (double v : u) d2 += (v - 0.5) * (v - 0.5);
        return d2 < r * r ? 2.0 * std::sqrt(r * r - d2) : 0.0;
    };
    return t;
}

TestIntegrand makeSingular(int dims) {
    TestIntegrand t{"singular", "prod u_i^(-1/2) / 2 (integrable singularity, infinite variance)", dims, {}, 0, {}, {}};
    makeSeparable(t, [](double u) { return 0.5 / std::sqrt(u); }, 1.0);
    // p(u) = (3/4) u^{-1/4} is less singular than f, so f/p = (2/3) u^{-1/4} has finite
    // variance (4/3 - 1 per coordinate): importance sampling repairs the infinite variance.
    t.importance = productDensity({[](double u) { return 0.75 / std::pow(u, 0.25); },
                                   [](double xi) { return std::pow(xi, 4.0 / 3.0); }});
    return t;
}

}  // namespace

const std::vector<std::string>& testIntegrandNames() {
    static const std::vector<std::string> names{"exp", "gaussian", "halfspace", "ball", "singular"};
    return names;
}

TestIntegrand makeTestIntegrand(const std::string& name, int dims) {
    if (dims < 1 || dims > kTestIntegrandMaxDims) throw std::invalid_argument("test integrand: dims must be 1..10");
    if (name == "exp") return makeExp(dims);
    if (name == "gaussian") return makeGaussian(dims);
    if (name == "halfspace") return makeHalfspace(dims);
    if (name == "ball") return makeBall(dims);
    if (name == "singular") return makeSingular(dims);
    throw std::invalid_argument("unknown test integrand \"" + name + "\"");
}

}  // namespace ps
