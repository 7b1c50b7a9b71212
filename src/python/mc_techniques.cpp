#include "python/mc_techniques.h"

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/mc_command.h"
#include "mc/convergence.h"
#include "mc/estimator.h"
#include "mc/sobol_matrices.h"
#include "mc/techniques.h"
#include "python/errors.h"
#include "python/mc_batched.h"

namespace py = pybind11;

namespace ps::python {

namespace {

// What the user gave: the integrand over [0,1)^dims and the optional parts some techniques need.
struct Problem {
    py::object f;
    int dims = 1;
    py::object partial;                      // "expected": (n, dims-1) points -> (n,)
    py::object importanceSample, importancePdf;  // "importance": (n, dims) -> (n, dims), (n, dims) -> (n,)
};

std::string techniqueNames() {
    std::string s;
    for (const Technique& t : techniques()) s += (s.empty() ? "" : ", ") + t.name;
    return s;
}

const Technique& checkedTechnique(const std::string& name, const Problem& p) {
    const Technique* t = findTechnique(name);
    if (!t) raiseValueError("unknown technique \"" + name + "\" (known: " + techniqueNames() + ")");
    if (name == "expected" && p.partial.is_none())
        raiseValueError("technique \"expected\" needs partial=: f integrated over the last coordinate, "
                        "a vectorised function of the first dims-1");
    if (name == "importance" && p.importanceSample.is_none())
        raiseValueError("technique \"importance\" needs importance=(sample, pdf)");
    if (name == "sobol" && p.dims > kSobolMaxDims)
        raiseValueError("technique \"sobol\" takes up to " + std::to_string(kSobolMaxDims) + " dimensions");
    return *t;
}

Problem makeProblem(py::object f, int dims, py::object partial, py::object importance) {
    if (dims < 1) raiseValueError("dims must be at least 1");
    if (!PyCallable_Check(f.ptr())) throw py::type_error("f must be callable");
    Problem p{std::move(f), dims, std::move(partial), py::none(), py::none()};
    if (!importance.is_none()) {
        auto pair = importance.cast<py::tuple>();
        if (pair.size() != 2) raiseValueError("importance= takes a pair (sample, pdf)");
        p.importanceSample = pair[0];
        p.importancePdf = pair[1];
    }
    return p;
}

// One run of the technique on the Python functions, in passes (mc_batched.h). The time is the
// whole run's, Python's evaluations and the passes included.
McEstimate runTechnique(const Problem& p, const Technique& tech, int n, Rng& rng) {
    Stopwatch clock;
    BatchedFunction f(p.f, "f");
    std::optional<BatchedFunction> partial, sample, pdf;
    TestIntegrand t;
    t.name = "python";
    t.dims = p.dims;
    t.f = [&f](std::span<const double> u) { return f(u); };
    // The order in which they are evaluated: the sampling map's points come first.
    std::vector<BatchedFunction*> order;
    if (!p.importanceSample.is_none()) {
        sample.emplace(p.importanceSample, "importance sample", p.dims);
        pdf.emplace(p.importancePdf, "importance pdf");
        ImportanceDensity density;
        density.pdf = [&pdf](std::span<const double> x) { return (*pdf)(x); };
        density.sample = [&sample](std::span<const double> u, std::span<double> x) { sample->map(u, x); };
        t.importance = density;
        order.push_back(&*sample);
        order.push_back(&*pdf);
    }
    if (!p.partial.is_none()) {
        partial.emplace(p.partial, "partial");
        t.partial = [&partial](std::span<const double> u) { return (*partial)(u); };
        order.push_back(&*partial);
    }
    order.push_back(&f);
    McEstimate e;
    const Rng start = rng;
    runInPasses(order, [&] {
        rng = start;
        e = tech.run(t, n, rng);
    });
    e.seconds = clock.seconds();
    return e;
}

double varianceOf(const McEstimate& e) { return e.standardError * e.standardError; }

}  // namespace

void registerMcTechniques(py::module_& mc) {
    py::class_<McEstimate>(mc, "Estimate", "One run of a technique: the estimate, its error and cost.")
        .def_readonly("value", &McEstimate::value)
        .def_readonly("standard_error", &McEstimate::standardError,
                      "the run's own estimate of its standard error (as if its samples were independent: "
                      "conservative for stratified and Sobol points)")
        .def_property_readonly("variance", &varianceOf, "standard_error squared: the estimate's variance V")
        .def_readonly("evaluations", &McEstimate::evaluations, "integrand evaluations the technique made")
        .def_readonly("seconds", &McEstimate::seconds, "wall time T of the run, Python's evaluations included")
        .def_property_readonly(
            "efficiency", [](const McEstimate& e) { return efficiency(varianceOf(e), e.seconds); }, "1/(V T)")
        .def("__repr__", [](const McEstimate& e) {
            return "Estimate(value=" + std::to_string(e.value) + ", standard_error=" + std::to_string(e.standardError) +
                   ", evaluations=" + std::to_string(e.evaluations) + ")";
        });

    mc.def(
        "techniques",
        [] {
            std::vector<std::pair<std::string, std::string>> list;
            for (const Technique& t : techniques()) list.emplace_back(t.name, t.description);
            return list;
        },
        "The techniques of pathspace mc as (name, description) pairs.");

    mc.def(
        "estimate",
        [](py::object f, int dims, int n, const std::string& technique, uint64_t seed, py::object partial,
           py::object importance) {
            if (n < 1) raiseValueError("n must be at least 1");
            Problem p = makeProblem(std::move(f), dims, std::move(partial), std::move(importance));
            const Technique& tech = checkedTechnique(technique, p);
            Rng rng(seed);
            return runTechnique(p, tech, n, rng);
        },
        py::arg("f"), py::arg("dims"), py::arg("n"), py::arg("technique") = "independent", py::arg("seed") = 0,
        py::arg("partial") = py::none(), py::arg("importance") = py::none(),
        "Estimate the integral of f over [0,1)^dims with one of techniques() and a budget of about n evaluations. "
        "f takes an (m, dims) float64 array of points and returns m values. partial (technique \"expected\") "
        "is f integrated over its last coordinate, a function of the first dims-1 (of one coordinate when dims "
        "is 1); importance=(sample, pdf) (technique \"importance\"): sample maps (m, dims) uniform points to "
        "(m, dims) points of density pdf. Returns an Estimate.");

    mc.def(
        "convergence",
        [](py::object f, int dims, double exact, std::vector<int> ns, const std::string& technique, int runs,
           uint64_t seed, py::object partial, py::object importance) {
            if (ns.empty()) raiseValueError("n: give at least one sample count");
            for (int n : ns)
                if (n < 1) raiseValueError("n: every sample count must be at least 1");
            if (runs < 2) raiseValueError("runs must be at least 2");
            Problem p = makeProblem(std::move(f), dims, std::move(partial), std::move(importance));
            const Technique& tech = checkedTechnique(technique, p);
            ConvergenceStudy study = studyConvergence(
                [&](int n, Rng& rng) { return runTechnique(p, tech, n, rng); }, exact, ns, runs, seed);
            // The keys and values of pathspace mc --json.
            nlohmann::json points = nlohmann::json::array();
            for (const ConvergencePoint& c : study.points) points.push_back(convergencePointJson(c));
            py::dict result;
            result["technique"] = technique;
            result["slope"] = study.slope;
            result["points"] = py::module_::import("json").attr("loads")(points.dump());
            return result;
        },
        py::arg("f"), py::arg("dims"), py::arg("exact"), py::arg("n"), py::arg("technique") = "independent",
        py::arg("runs") = 16, py::arg("seed") = 0, py::arg("partial") = py::none(),
        py::arg("importance") = py::none(),
        "pathspace mc's convergence study: `runs` independent runs at each sample count in n; returns "
        "{\"technique\", \"slope\" (of log RMSE against log evaluations), \"points\": one dictionary per count "
        "with the keys of pathspace mc --json (n, evaluations, mean, standard_error, reported_error, rmse, "
        "seconds, efficiency)}.");
}

}  // namespace ps::python
