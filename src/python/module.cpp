// `import pathspace`: load a pbrt-v4 scene, render it with the command line's options, get
// numpy arrays and the statistics (docs/python.md).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <filesystem>

#include "python/errors.h"
#include "python/mc_module.h"
#include "python/render_call.h"
#include "python/result_object.h"
#include "python/scene_object.h"
#include "scene/parser.h"
#include "transport/render_monitor.h"
#include "util/error.h"

namespace py = pybind11;
using namespace ps;
using namespace ps::python;

namespace {

// Parses a scene (its warnings in file order); a problem raises SceneError.
template <typename Parse>
SceneObject loadScene(Parse parse, std::string file) {
    try {
        py::gil_scoped_release nogil;
        const HeldWarnings inFileOrder;
        return SceneObject(parse(), std::move(file));
    } catch (const InputError& e) {
        raiseSceneError(e);
    }
}

Vec3 vec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

// A number is a "float" parameter, three numbers an "rgb" one.
void setMaterial(SceneObject& scene, const std::string& name, const std::string& parameter, py::object value) {
    Param p;
    p.name = parameter;
    if (py::isinstance<py::sequence>(value) && !py::isinstance<py::str>(value)) {
        for (const py::handle& v : value) p.numbers.push_back(v.cast<double>());
        if (p.numbers.size() != 3) raiseValueError("set_material: a colour is three numbers (\"rgb\")");
        p.type = ParamType::RGB;
        p.typeName = "rgb";
    } else {
        p.numbers = {value.cast<double>()};
        p.type = ParamType::Float;
        p.typeName = "float";
    }
    scene.setMaterialParam(name, std::move(p));
}

}  // namespace

PYBIND11_MODULE(pathspace, m) {
    m.doc() = "pathspace: a physically based renderer (Veach's robust Monte Carlo light transport).";
    m.attr("__version__") = PATHSPACE_VERSION;
    registerErrors(m);
    registerResult(m);
    registerMc(m);

    py::class_<Progress>(m, "Progress", "The figures of the command line's progress line, given to progress=.")
        .def_property_readonly("phase", [](const Progress& p) { return std::string(p.phase); },
                               "\"rendering\", or a Metropolis render's \"bootstrap\"")
        .def_readonly("fraction", &Progress::fraction, "done, from 0 to 1")
        .def_readonly("elapsed", &Progress::elapsed, "seconds since the phase began")
        .def_readonly("eta", &Progress::eta, "estimated seconds left (0 on the final report)")
        .def_readonly("final", &Progress::final, "the phase's last report")
        .def("__repr__", [](const Progress& p) {
            return "<pathspace.Progress " + std::string(p.phase) + " " + std::to_string(100 * p.fraction) + "%>";
        });

    py::class_<SceneObject>(m, "Scene", py::dynamic_attr(),
                            "A parsed pbrt-v4 scene (pathspace.load, pathspace.load_string).")
        .def_property_readonly("file", &SceneObject::file)
        .def("set_resolution", &SceneObject::setResolution, py::arg("width"), py::arg("height"),
             "Overrides the Film's xresolution and yresolution.")
        .def(
            "set_camera",
            [](SceneObject& s, std::array<float, 3> eye, std::array<float, 3> target, std::array<float, 3> up) {
                s.setCamera(vec(eye), vec(target), vec(up));
            },
            py::arg("position"), py::arg("look_at"), py::arg("up") = std::array<float, 3>{0, 1, 0},
            "Places the camera as `LookAt position look_at up` would, replacing its whole transform.")
        .def(
            "set_material", &setMaterial, py::arg("name"), py::arg("parameter"), py::arg("value"),
            "Sets a parameter of the named material (MakeNamedMaterial): a number (\"float\") or three (\"rgb\").")
        .def("set_light_scale", &SceneObject::setLightScale, py::arg("index"), py::arg("scale"),
             "Sets a light's \"scale\"; the index is into Scene.lights.")
        .def_property_readonly("lights", &SceneObject::lights,
                               "The lights set_light_scale names by index: LightSource directives, then "
                               "AreaLightSource ones, in file order.")
        .def(
            "render",
            [](py::object self, py::kwargs options) {
                return renderScene(self, self.cast<SceneObject&>(), options);
            },
            "render(**options) -> Result. The options are `pathspace render`'s, spelt as Python names: spp, "
            "time, threads, seed, maxdepth, integrator, mis, sampler, adaptive, color, aovs=[...], "
            "crop=(x0, x1, y0, y1), pixelbounds=(...), max_memory and the Metropolis ones (chains, bootstrap, "
            "large_step_probability, ...); also bdpt_strategies=True and progress= (a callable given each "
            "Progress, True for a tqdm bar when tqdm is installed, else the command line's bar, \"tqdm\" or "
            "\"stderr\"). Bad values raise ValueError with the command line's message; Ctrl-C raises "
            "KeyboardInterrupt, whose .result holds the image so far.");

    m.def(
        "load",
        [](const std::filesystem::path& path) {
            const std::string p = path.string();
            return loadScene([&] { return parseSceneFile(p); }, p);
        },
        py::arg("path"), "Reads a pbrt-v4 scene file (and the files it includes). Raises SceneError.");
    m.def(
        "load_string",
        [](const std::string& text, const std::filesystem::path& baseDir) {
            const std::string base = baseDir.string();
            return loadScene([&] { return parseSceneString(text, base); }, "<string>");
        },
        py::arg("text"), py::arg("base_dir") = ".",
        "Reads a scene from text; relative paths in it (meshes, textures, Include) resolve against base_dir. "
        "Raises SceneError.");
}
