#include "python/progress_bar.h"

#include <memory>
#include <string>

#include "python/errors.h"

namespace py = pybind11;

namespace ps::python {

namespace {

// tqdm's bar class (tqdm.auto's, which draws a widget in a notebook), or None without tqdm.
py::object tqdmClass() {
    for (const char* module : {"tqdm.auto", "tqdm"}) {
        try {
            return py::module_::import(module).attr("tqdm");
        } catch (const py::error_already_set& e) {
            if (!e.matches(PyExc_ImportError) && !e.matches(PyExc_AttributeError)) throw;
        }
    }
    return py::none();
}

class TqdmBar {
public:
    explicit TqdmBar(py::object cls) : cls_(std::move(cls)) {}

    void report(const Progress& p) {
        if (bar_.is_none() || phase_ != p.phase) {
            close();
            phase_ = p.phase;
            bar_ = cls_(py::arg("total") = 100, py::arg("desc") = phase_, py::arg("unit") = "%",
                        py::arg("bar_format") = "{desc}: {percentage:3.0f}%|{bar}| [{elapsed}<{remaining}]");
            done_ = 0;
        }
        // Whole percents: tqdm's n stays an integer, and a report that adds nothing is skipped.
        const int target = int(100 * p.fraction);
        if (target > done_) {
            bar_.attr("update")(target - done_);
            done_ = target;
        }
        if (p.final) close();
    }

    void close() {
        if (bar_.is_none()) return;
        py::object bar = std::move(bar_);
        bar_ = py::none();
        bar.attr("close")();
    }

private:
    py::object cls_, bar_ = py::none();
    std::string phase_;
    int done_ = 0;
};

ProgressReporting tqdmReporting(py::object cls) {
    auto bar = std::make_shared<TqdmBar>(std::move(cls));
    ProgressReporting r;
    r.report = [bar](const Progress& p) { bar->report(p); };
    r.finish = [bar] {
        try {
            bar->close();
        } catch (const py::error_already_set&) {
            // A bar that cannot close is not worth the render's result.
        }
    };
    return r;
}

ProgressReporting stderrReporting() {
    ProgressReporting r;
    r.stderrBar = true;
    return r;
}

}  // namespace

ProgressReporting chooseProgress(const py::object& progress) {
    if (progress.is_none() || progress.ptr() == Py_False) return {};
    if (progress.ptr() == Py_True) {
        py::object cls = tqdmClass();
        return cls.is_none() ? stderrReporting() : tqdmReporting(cls);
    }
    if (py::isinstance<py::str>(progress)) {
        const std::string name = progress.cast<std::string>();
        if (name == "stderr") return stderrReporting();
        if (name != "tqdm")
            raiseValueError("progress: expected True, False, \"tqdm\", \"stderr\" or a callable, got \"" + name + "\"");
        py::object cls = tqdmClass();
        if (!cls.is_none()) return tqdmReporting(cls);
        if (PyErr_WarnEx(PyExc_RuntimeWarning,
                         "progress=\"tqdm\": tqdm is not installed; showing the command line's progress bar on stderr",
                         1) < 0)
            throw py::error_already_set();
        return stderrReporting();
    }
    if (!PyCallable_Check(progress.ptr()))
        raiseValueError("progress: expected True, False, \"tqdm\", \"stderr\" or a callable");
    ProgressReporting r;
    r.report = [progress](const Progress& p) { progress(p); };
    return r;
}

}  // namespace ps::python
