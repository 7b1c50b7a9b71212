// pathspace.Result: what a render returns. Its arrays are views of the render's own buffers
// (no copy), each keeping them alive, so an array outlives the result and the scene.
#pragma once
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "image/image.h"
#include "transport/renderer.h"

namespace ps::python {

struct RenderOutput {
    RenderResult result;
    std::vector<std::pair<std::string, Image>> strategies;  // BDPT's, when asked for
    std::string stats;  // as --stats writes them (JSON)
    bool interrupted = false;
};

void registerResult(pybind11::module_& m);

}  // namespace ps::python
