// A vectorised Python function seen by the toolbox's estimators (src/mc), which call their
// integrand one point at a time, as if it were a scalar C++ function: the estimator is run in
// passes from the same random state. In a pass, a call whose point was met in an earlier pass
// gets that point's value; a new point is noted and gets 0. Between passes the noted points go
// to the Python function in one call, as an (m, dims) float64 array. When a pass meets no new
// point, its estimate is the estimator's on the function itself.
//
// A point that differs from the one met at the same call in an earlier pass (an estimator that
// chose its later points from earlier values, such as the two-stage adaptive one) drops that
// call's value and every later one. Several functions (an importance density's sampling map,
// its pdf and the integrand) are evaluated in the order they are listed (BatchedPasses): only
// the first with new points is evaluated after a pass, since the others' new points may have
// been computed from its placeholder values.
#pragma once
#include <pybind11/pybind11.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace ps::python {

class BatchedFunction {
public:
    // outDims 0: fn returns (m,) values; outDims k > 0: fn returns (m, k) points.
    BatchedFunction(pybind11::object fn, std::string name, int outDims = 0);

    // The value at u (scalar functions) or its first coordinate; writes the point for maps.
    double operator()(std::span<const double> u);
    void map(std::span<const double> u, std::span<double> out);

    void startPass() { cursor_ = 0; }
    bool hasNew() const { return !newPoints_.empty(); }
    void discardNew();
    void evaluateNew();  // calls Python once; throws pybind11 errors, ValueError on a bad shape
    int64_t pythonPoints() const { return pythonPoints_; }

private:
    const double* lookup(std::span<const double> u);  // the known output, or nullptr (noted)

    pybind11::object fn_;
    std::string name_;
    int outDims_;
    int inDims_ = -1;
    std::vector<double> knownPoints_, knownOutputs_;  // call i: inDims_ / max(1, outDims_) each
    size_t known_ = 0, cursor_ = 0;
    std::vector<double> newPoints_;
    int64_t pythonPoints_ = 0;
};

// Runs `pass` until it meets no new point; returns how many passes it took.
int runInPasses(const std::vector<BatchedFunction*>& functions, const std::function<void()>& pass);

}  // namespace ps::python
