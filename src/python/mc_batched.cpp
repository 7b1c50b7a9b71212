#include "python/mc_batched.h"

#include <pybind11/numpy.h>

#include <algorithm>
#include <cstring>

#include "python/errors.h"

namespace py = pybind11;

namespace ps::python {

BatchedFunction::BatchedFunction(py::object fn, std::string name, int outDims)
    : fn_(std::move(fn)), name_(std::move(name)), outDims_(outDims) {}

const double* BatchedFunction::lookup(std::span<const double> u) {
    if (inDims_ < 0) inDims_ = int(u.size());
    const size_t in = size_t(inDims_), out = size_t(std::max(1, outDims_));
    if (cursor_ < known_) {
        if (std::memcmp(&knownPoints_[cursor_ * in], u.data(), in * sizeof(double)) == 0)
            return &knownOutputs_[cursor_++ * out];
        // Another point at this call than before: this value and the later ones are stale.
        known_ = cursor_;
        knownPoints_.resize(known_ * in);
        knownOutputs_.resize(known_ * out);
    }
    newPoints_.insert(newPoints_.end(), u.begin(), u.end());
    ++cursor_;
    return nullptr;
}

double BatchedFunction::operator()(std::span<const double> u) {
    const double* v = lookup(u);
    return v ? *v : 0.0;
}

void BatchedFunction::map(std::span<const double> u, std::span<double> out) {
    const double* v = lookup(u);
    for (size_t i = 0; i < out.size(); ++i) out[i] = v ? v[i] : 0.0;
}

void BatchedFunction::discardNew() { newPoints_.clear(); }

void BatchedFunction::evaluateNew() {
    const py::ssize_t m = py::ssize_t(newPoints_.size()) / inDims_;
    py::array_t<double> points({m, py::ssize_t(inDims_)});
    std::copy(newPoints_.begin(), newPoints_.end(), points.mutable_data());
    py::object returned = fn_(points);
    auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(returned);
    if (!values) throw py::error_already_set();
    const bool scalar = outDims_ == 0;
    const bool ok = scalar ? values.ndim() == 1 && values.shape(0) == m
                           : values.ndim() == 2 && values.shape(0) == m && values.shape(1) == outDims_;
    if (!ok) {
        std::string shape = "(";
        for (py::ssize_t d = 0; d < values.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(values.shape(d));
        shape += values.ndim() == 1 ? ",)" : ")";
        std::string want = scalar ? "(" + std::to_string(m) + ",)"
                                  : "(" + std::to_string(m) + ", " + std::to_string(outDims_) + ")";
        raiseValueError(name_ + " returned an array of shape " + shape + " for " + std::to_string(m) +
                        " points; expected " + want);
    }
    knownPoints_.insert(knownPoints_.end(), newPoints_.begin(), newPoints_.end());
    knownOutputs_.insert(knownOutputs_.end(), values.data(), values.data() + values.size());
    known_ += size_t(m);
    pythonPoints_ += m;
    newPoints_.clear();
}

int runInPasses(const std::vector<BatchedFunction*>& functions, const std::function<void()>& pass) {
    // Each pass evaluates at least one new point, so this bounds only a runaway estimator.
    constexpr int kMaxPasses = 64;
    for (int passes = 1; passes <= kMaxPasses; ++passes) {
        for (BatchedFunction* f : functions) f->startPass();
        pass();
        auto first = std::find_if(functions.begin(), functions.end(), [](BatchedFunction* f) { return f->hasNew(); });
        if (first == functions.end()) return passes;
        for (auto later = first + 1; later != functions.end(); ++later) (*later)->discardNew();
        (*first)->evaluateNew();
    }
    throw std::runtime_error("mc: the estimator kept asking for new points after 64 passes");
}

}  // namespace ps::python
