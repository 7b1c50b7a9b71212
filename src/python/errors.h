// How the renderer's errors reach Python: a scene error as pathspace.SceneError (a ValueError
// with .file, .line and .column), an option's bad value as ValueError, each with the message
// the command line prints.
#pragma once
#include <pybind11/pybind11.h>

#include <string>

namespace ps {

class InputError;

namespace python {

void registerErrors(pybind11::module_& m);

// Sets (or raises) pathspace.SceneError for `e`, located or not.
void setSceneError(const InputError& e);
[[noreturn]] void raiseSceneError(const InputError& e);
[[noreturn]] void raiseValueError(const std::string& message);

}  // namespace python
}  // namespace ps
