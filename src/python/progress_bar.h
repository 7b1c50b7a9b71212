// What render(progress=...) does with the render's progress reports (Monitor's figures):
//   None, False        nothing
//   a callable         called with each pathspace.Progress
//   True               a tqdm bar when tqdm is installed, else the command line's bar on stderr
//   "tqdm"             a tqdm bar; without tqdm, a warning and the command line's bar
//   "stderr"           the command line's bar on stderr
// A tqdm bar counts percent, one bar per phase (a Metropolis render's "bootstrap", then
// "rendering"), and is closed after the render however it ends.
#pragma once
#include <pybind11/pybind11.h>

#include <functional>

#include "transport/render_monitor.h"

namespace ps::python {

struct ProgressReporting {
    bool stderrBar = false;
    ProgressCallback report;      // called with the GIL held; may throw Python's errors
    std::function<void()> finish;  // with the GIL, once the render is over (never throws)
};

// Raises ValueError for another string or value.
ProgressReporting chooseProgress(const pybind11::object& progress);

}  // namespace ps::python
