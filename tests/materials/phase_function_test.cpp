// Henyey-Greenstein sampling (materials/phase_function.h), which media scatter by: Pearson's
// chi-square of sampled directions against p integrated over a 20 x 40 grid of the sphere.
#include <gtest/gtest.h>

#include "materials/phase_function.h"
#include "mc/rng.h"
#include "stats.h"

using namespace ps;
using namespace ps::test;

TEST(HGPhaseFunction, ChiSquareOfSamplesAgainstPdf) {
    const SphereGrid grid(20, 40);
    const int n = 400000;
    const float gs[] = {-0.8f, -0.3f, 0.0f, 0.4f, 0.9f};
    const double alpha = sidak(1e-3, 5);
    for (float g : gs) {
        HGPhaseFunction ph(g);
        const Vec3 wo = normalize(Vec3(0.3f, -0.4f, 0.6f));
        // The lobe about -wo is narrow for |g| near 1: a fine quadrature per cell.
        std::vector<double> expected = grid.integrate([&](Vec3 wi) { return ph.p(wo, wi); }, 24);
        std::vector<double> observed(expected.size(), 0.0);
        Rng rng(uint64_t(500 + 100 * g));
        for (int i = 0; i < n; ++i) {
            float pdf = 0;
            const Vec3 wi = ph.sample(wo, {rng.uniform(), rng.uniform()}, &pdf);
            observed[grid.cellOf(wi)] += 1;
        }
        for (double& e : expected) e *= n;
        ChiSquareResult r = chiSquare(observed, expected);
        std::printf("[ chi2     ] HG g=%5.2f chi2=%8.1f dof=%3d p=%.3g\n", g, r.chi2, r.dof, r.pValue);
        EXPECT_GT(r.pValue, alpha) << "g=" << g << " chi2=" << r.chi2 << " dof=" << r.dof;
    }
}
