// Integrands over [0,1)^s with exact integrals, for measuring estimators (thesis ch. 2's
// variance-reduction techniques, each with a case it is meant for):
//   exp       prod_i e^{u_i}: smooth and monotone in every coordinate
//   gaussian  prod_i exp(-c^2 (u_i - 1/2)^2), c = 2 (Genz's Gaussian peak): smooth, and
//             symmetric about 1/2, so f(1-u) = f(u)
//   halfspace the indicator of sum_i u_i < 0.4 s: a discontinuity not aligned with the axes
//   ball      the indicator of |u - (1/2,...)| < 0.45: a curved discontinuity
//   singular  prod_i u_i^{-1/2} / 2: an integrable singularity; f has infinite variance
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "mc/importance_sampling.h"
#include "mc/mc_estimate.h"

namespace ps {

struct TestIntegrand {
    std::string name, description;
    int dims = 1;
    Integrand f;
    double exact = 0;
    // Integral of f over the last coordinate given the first dims-1 (expected values).
    Integrand partial;
    // A density resembling f, when there is a natural one (the separable integrands).
    std::optional<ImportanceDensity> importance;
};

constexpr int kTestIntegrandMaxDims = 10;

const std::vector<std::string>& testIntegrandNames();
// Throws std::invalid_argument for an unknown name or dims outside 1..10.
TestIntegrand makeTestIntegrand(const std::string& name, int dims);

}  // namespace ps
