#include "python/result_object.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

#include "python/errors.h"
#include "util/error.h"

namespace py = pybind11;

namespace ps::python {

namespace {

using Owner = std::shared_ptr<RenderOutput>;

// A read-only view of `img` (row 0 the top): (H, W, 3), or (H, W) for a grey image (its first
// channel; the three are equal). The array's base holds the render's output alive.
py::object view(const Owner& owner, const Image& img, bool grey) {
    if (img.width <= 0 || img.height <= 0) return py::none();
    auto* keep = new Owner(owner);
    py::capsule base(keep, [](void* p) { delete static_cast<Owner*>(p); });
    const py::ssize_t h = img.height, w = img.width, f = sizeof(float);
    std::vector<py::ssize_t> shape{h, w}, strides{w * 3 * f, 3 * f};
    if (!grey) {
        shape.push_back(3);
        strides.push_back(f);
    }
    py::array a(py::dtype::of<float>(), shape, strides, img.rgb.data(), base);
    // Shared by every view and by write(): a change would alter them all. np.array(a) copies.
    a.attr("flags").attr("writeable") = false;
    return a;
}

py::dict aovs(const Owner& o) {
    py::dict d;
    if (o->result.variance.width > 0) d["variance"] = view(o, o->result.variance, true);
    return d;
}

}  // namespace

void registerResult(py::module_& m) {
    py::class_<RenderOutput, Owner>(m, "Result", "What Scene.render returns.")
        .def_property_readonly(
            "image", [](const Owner& o) { return view(o, o->result.image, false); },
            "The image: float32 (height, width, 3), linear RGB, row 0 the top; read-only and shared with the "
            "result (no copy).")
        .def_property_readonly(
            "variance", [](const Owner& o) { return view(o, o->result.variance, true); },
            "With aovs=['variance']: each pixel's variance of its mean luminance, float32 (height, width); else None.")
        .def_property_readonly("aovs", &aovs, "The extra outputs asked for by aovs=[...], by name.")
        .def_property_readonly(
            "strategies",
            [](const Owner& o) -> py::object {
                if (o->strategies.empty()) return py::none();
                py::dict d;
                for (const auto& [name, img] : o->strategies) d[py::str(name)] = view(o, img, false);
                return d;
            },
            "With bdpt_strategies=True: BDPT's per-strategy images up to depth 5, by name (s<S>_t<T> "
            "MIS-weighted, summing to the image, and s<S>_t<T>_unweighted); else None.")
        .def_property_readonly(
            "stats", [](const Owner& o) { return py::module_::import("json").attr("loads")(o->stats); },
            "The render's statistics: the dictionary `pathspace render --stats` writes.")
        .def_property_readonly(
            "interrupted", [](const Owner& o) { return o->interrupted; }, "True when Ctrl-C stopped the render early.")
        .def(
            "write",
            [](const Owner& o, const std::filesystem::path& path, const std::string& aov) {
                const Image* img = &o->result.image;
                if (aov == "variance") {
                    if (o->result.variance.width <= 0)
                        raiseValueError("write(aov=\"variance\") needs a render with aovs=[\"variance\"]");
                    img = &o->result.variance;
                } else if (!aov.empty()) {
                    raiseValueError("write: unknown aov \"" + aov + "\" (known: variance)");
                }
                const std::string p = path.string();
                py::gil_scoped_release nogil;
                writeImage(p, *img);  // throws InputError: a ValueError
            },
            py::arg("path"), py::arg("aov") = "",
            "Writes the image (or the AOV named) as .exr (float32), .png (sRGB 8-bit, clamped) or .pfm, as the "
            "command line's -o does.")
        .def("__repr__", [](const Owner& o) {
            const Image& i = o->result.image;
            return "<pathspace.Result " + std::to_string(i.width) + "x" + std::to_string(i.height) + ", " +
                   std::to_string(o->result.meanSpp) + " spp" + (o->interrupted ? ", interrupted" : "") + ">";
        });
}

}  // namespace ps::python
