// Scene.render(**options): the command line's render options, given as keyword arguments.
#pragma once
#include <pybind11/pybind11.h>

namespace ps::python {

class SceneObject;

// Renders `scene` with the options (spp=, integrator=, ...: `pathspace render`'s, checked by
// the same code with the same messages) and returns a pathspace.Result. Raises
// KeyboardInterrupt on Ctrl-C, its .result the image so far.
pybind11::object renderScene(pybind11::object sceneObject, SceneObject& scene, const pybind11::kwargs& options);

}  // namespace ps::python
