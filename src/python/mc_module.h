// pathspace.mc: the Monte Carlo toolbox's point sets (src/mc) for integrands written in Python.
#pragma once
#include <pybind11/pybind11.h>

namespace ps::python {

void registerMc(pybind11::module_& m);

}  // namespace ps::python
