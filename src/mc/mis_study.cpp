#include "mc/mis_study.h"

#include <chrono>
#include <cmath>

#include "mc/rng.h"

namespace ps {

namespace {

constexpr double kPi = 3.14159265358979323846;

// 1 - cos(x) without cancellation for the smallest lights.
double oneMinusCos(double x) {
    const double h = std::sin(x / 2);
    return 2 * h * h;
}

// The lobe's density at a direction cosAlpha from the mirror direction (+z). The light's
// centre is c = (sin offset, 0, cos offset), with the tangent (cos offset, 0, -sin offset)
// and +y completing its frame.
double lobeDensity(double exponent, double cosAlpha) {
    return cosAlpha > 0 ? (exponent + 1) / (2 * kPi) * std::pow(cosAlpha, exponent) : 0;
}

}  // namespace

double GlossyHighlight::exact() const {
    // Midpoint rule in (rho, phi) about the light's centre: smooth and periodic in phi.
    const int nRho = 2000, nPhi = 512;
    const double sinO = std::sin(offset), cosO = std::cos(offset);
    double sum = 0;
    for (int i = 0; i < nRho; ++i) {
        const double rho = lightRadius * (i + 0.5) / nRho;
        const double sr = std::sin(rho), cr = std::cos(rho);
        double ring = 0;
        for (int j = 0; j < nPhi; ++j) {
            const double phi = 2 * kPi * (j + 0.5) / nPhi;
            ring += lobeDensity(exponent, cr * cosO - sr * std::cos(phi) * sinO);
        }
        sum += ring * sr;
    }
    return sum * (lightRadius / nRho) * (2 * kPi / nPhi);
}

GlossyHighlight::Sample GlossyHighlight::sampleLight(double u1, double u2) const {
    const double omc = oneMinusCos(lightRadius);
    const double a = u1 * omc;  // 1 - cos(rho), uniform over the cap's solid angle
    const double cr = 1 - a, sr = std::sqrt(std::fmax(0.0, a * (2 - a)));
    const double phi = 2 * kPi * u2;
    const double sinO = std::sin(offset), cosO = std::cos(offset);
    const double z = sr * std::cos(phi) * -sinO + cr * cosO;
    Sample s;
    s.pLight = 1 / (2 * kPi * omc);
    s.pBsdf = lobeDensity(exponent, z);
    s.f = s.pBsdf;
    return s;
}

GlossyHighlight::Sample GlossyHighlight::sampleBsdf(double u1, double u2) const {
    const double ca = std::pow(u1, 1 / (exponent + 1));
    const double sa = std::sqrt(std::fmax(0.0, 1 - ca * ca));
    const double phi = 2 * kPi * u2;
    const double sinO = std::sin(offset), cosO = std::cos(offset);
    const double cosToCentre = sa * std::cos(phi) * sinO + ca * cosO;  // w = (sa cos phi, sa sin phi, ca)
    Sample s;
    s.pBsdf = lobeDensity(exponent, ca);
    const bool inCap = 1 - cosToCentre <= oneMinusCos(lightRadius);
    s.pLight = inCap ? 1 / (2 * kPi * oneMinusCos(lightRadius)) : 0;
    s.f = inCap ? s.pBsdf : 0;
    return s;
}

std::vector<MisStrategy> misStudyStrategies() {
    MisWeighting power, cutoff;
    power.heuristic = MisHeuristic::Power;
    cutoff.heuristic = MisHeuristic::Cutoff;
    return {{"balance", MisWeighting(MisHeuristic::Balance), -1},
            {"power:2", power, -1},
            {"cutoff:0.1", cutoff, -1},
            {"maximum", MisWeighting(MisHeuristic::Maximum), -1},
            {"light alone", {}, 0},
            {"bsdf alone", {}, 1}};
}

std::vector<MisStudyCell> runMisStudy(const std::vector<MisStrategy>& strategies, int samples, uint64_t seed) {
    // Fig. 9.2's grid: each light 4x the radius of the last, each lobe 10x sharper. The
    // mirror direction falls inside every light, half its radius from the centre.
    const double radii[] = {0.005, 0.02, 0.08, 0.32};
    const double exponents[] = {10, 100, 1000, 10000};
    std::vector<MisStudyCell> cells;
    for (double radius : radii)
        for (double exponent : exponents) {
            MisStudyCell cell;
            cell.setup = GlossyHighlight{radius, radius / 2, exponent};
            cell.exact = cell.setup.exact();
            const GlossyHighlight& g = cell.setup;
            for (const MisStrategy& st : strategies) {
                // The same random numbers for every strategy of a case: their differences
                // are the weights' alone.
                Rng rng(hashCombine(seed, uint64_t(cells.size())));
                const auto start = std::chrono::steady_clock::now();
                double mean = 0, m2 = 0;  // Welford
                for (int i = 0; i < samples; ++i) {
                    const double u[4] = {rng.uniformDouble(), rng.uniformDouble(), rng.uniformDouble(),
                                         rng.uniformDouble()};
                    double F;
                    if (st.alone == 0) {
                        const auto a = g.sampleLight(u[0], u[1]), b = g.sampleLight(u[2], u[3]);
                        F = (a.f / a.pLight + b.f / b.pLight) / 2;
                    } else if (st.alone == 1) {
                        const auto a = g.sampleBsdf(u[0], u[1]), b = g.sampleBsdf(u[2], u[3]);
                        F = (a.f > 0 ? a.f / a.pBsdf : 0) + (b.f > 0 ? b.f / b.pBsdf : 0);
                        F /= 2;
                    } else {
                        // Eq. 9.3 with one sample per technique.
                        const auto a = g.sampleLight(u[0], u[1]), b = g.sampleBsdf(u[2], u[3]);
                        F = 0;
                        if (a.f > 0) F += st.mis.weight(a.pLight, a.pBsdf) * a.f / a.pLight;
                        if (b.f > 0) F += st.mis.weight(b.pBsdf, b.pLight) * b.f / b.pBsdf;
                    }
                    const double d = F - mean;
                    mean += d / (i + 1);
                    m2 += d * (F - mean);
                }
                cell.mean.push_back(mean);
                cell.variance.push_back(samples > 1 ? m2 / (samples - 1) : 0);
                cell.seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
            }
            cells.push_back(std::move(cell));
        }
    return cells;
}

}  // namespace ps
