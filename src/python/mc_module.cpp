#include "python/mc_module.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "mc/mis_study.h"
#include "mc/point_sets.h"
#include "mc/rng.h"
#include "python/errors.h"
#include "python/mc_techniques.h"

namespace py = pybind11;

namespace ps::python {

namespace {

// The points as a (count, dims) float64 array that owns the set (no copy).
py::array points(const std::string& name, int n, int dims, uint64_t seed) {
    const std::optional<PointSetKind> kind = pointSetKindFromName(name);
    if (!kind) raiseValueError("points: unknown point set \"" + name + "\" (known: independent, stratified, lhs, sobol)");
    if (n < 1 || dims < 1) raiseValueError("points: n and dims must be at least 1");
    Rng rng(seed);
    auto set = std::make_unique<PointSet>();
    try {
        *set = generatePoints(*kind, n, dims, rng);
    } catch (const std::invalid_argument& e) {
        raiseValueError(std::string("points: ") + e.what());
    }
    const double* data = set->data.data();
    const py::ssize_t count = set->n, d = set->dims;
    py::capsule owner(set.release(), [](void* p) { delete static_cast<PointSet*>(p); });
    return py::array_t<double>({count, d}, data, owner);
}

// `pathspace mc --study mis` as a list of cases, each a dict with the light's radius, the
// lobe's exponent, the exact integral and each strategy's mean, variance and seconds.
py::list misStudy(int samples, uint64_t seed) {
    if (samples < 2) raiseValueError("mis_study: samples must be at least 2");
    const std::vector<MisStrategy> strategies = misStudyStrategies();
    py::list out;
    for (const MisStudyCell& c : runMisStudy(strategies, samples, seed)) {
        py::dict per;
        for (size_t i = 0; i < strategies.size(); ++i) {
            py::dict d;
            d["mean"] = c.mean[i];
            d["variance"] = c.variance[i];
            d["seconds"] = c.seconds[i];
            per[py::str(strategies[i].name)] = d;
        }
        py::dict cell;
        cell["light_radius"] = c.setup.lightRadius;
        cell["exponent"] = c.setup.exponent;
        cell["integral"] = c.exact;
        cell["strategies"] = per;
        out.append(cell);
    }
    return out;
}

}  // namespace

void registerMc(py::module_& m) {
    py::module_ mc = m.def_submodule("mc", "The Monte Carlo toolbox of the thesis's chapter 2 (pathspace mc).");
    mc.def("points", &points, py::arg("name"), py::arg("n"), py::arg("dims"), py::arg("seed") = 0,
           "n randomised points in [0,1)^dims as a (count, dims) float64 array: \"independent\", \"stratified\" "
           "(a k^dims grid, k = floor(n^(1/dims)): count may be below n), \"lhs\" (Latin hypercube) or \"sobol\" "
           "(Owen-scrambled, up to 10 dimensions). Each point is uniform: the mean of f over them is an unbiased "
           "estimate of f's integral; the same seed gives the same points.");
    mc.def("mis_study", &misStudy, py::arg("samples") = 200000, py::arg("seed") = 1,
           "Thesis ch. 9's glossy highlights (pathspace mc --study mis): for 16 cases of light size and lobe "
           "sharpness, each MIS heuristic's (balance, power:2, cutoff:0.1, maximum) and each technique's alone "
           "mean, variance and seconds over `samples` estimates of two samples each.");
    registerMcTechniques(mc);
}

}  // namespace ps::python
