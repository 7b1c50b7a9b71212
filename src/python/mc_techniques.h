// pathspace.mc.estimate, .convergence and .techniques: the toolbox's techniques (src/mc/
// techniques.h, those of `pathspace mc`) and its convergence study (mc/convergence.h) on a
// vectorised Python integrand, through BatchedFunction (mc_batched.h).
#pragma once
#include <pybind11/pybind11.h>

namespace ps::python {

void registerMcTechniques(pybind11::module_& mc);

}  // namespace ps::python
