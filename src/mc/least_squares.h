// Small dense linear algebra for the regression estimator: solve a symmetric positive
// definite system (the normal equations) by Cholesky factorisation.
#pragma once
#include <optional>
#include <vector>

namespace ps {

// Solves A x = b for symmetric positive definite A (n x n, row-major). nullopt if A is not
// numerically positive definite (e.g. a control that is constant over the samples).
std::optional<std::vector<double>> solveSpd(const std::vector<double>& a, const std::vector<double>& b, int n);

}  // namespace ps
