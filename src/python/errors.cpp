#include "python/errors.h"

#include "util/error.h"

namespace py = pybind11;

namespace ps::python {

namespace {

PyObject* gSceneError = nullptr;  // pathspace.SceneError, alive as long as the module

}  // namespace

void registerErrors(py::module_& m) {
    static py::exception<InputError> sceneError(m, "SceneError", PyExc_ValueError);
    sceneError.doc() = "A problem in a scene file: .file, .line and .column say where (None when it has no place).";
    gSceneError = sceneError.ptr();
    // Input errors met where no caller chose their type: located ones are the scene's.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            if (!e.where().file.empty())
                setSceneError(e);
            else
                PyErr_SetString(PyExc_ValueError, printableMessage(e.what()).c_str());
        }
    });
}

void setSceneError(const InputError& e) {
    py::object type = py::reinterpret_borrow<py::object>(gSceneError);
    py::object error = type(printableMessage(e.what()));
    const SourceLoc& at = e.where();
    error.attr("file") = at.file.empty() ? py::none() : py::object(py::str(at.file));
    error.attr("line") = at.line > 0 ? py::object(py::int_(at.line)) : py::none();
    error.attr("column") = at.line > 0 ? py::object(py::int_(at.column)) : py::none();
    PyErr_SetObject(gSceneError, error.ptr());
}

void raiseSceneError(const InputError& e) {
    setSceneError(e);
    throw py::error_already_set();
}

void raiseValueError(const std::string& message) { throw py::value_error(printableMessage(message)); }

}  // namespace ps::python
