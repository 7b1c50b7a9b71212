#include "python/render_call.h"

#include <algorithm>
#include <csignal>
#include <exception>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "app/command_line.h"
#include "app/interrupt.h"
#include "app/render_options.h"
#include "python/errors.h"
#include "python/progress_bar.h"
#include "python/result_object.h"
#include "python/scene_object.h"
#include "transport/bdpt.h"
#include "transport/strategy_images.h"
#include "util/error.h"
#include "util/memory_limit.h"

namespace py = pybind11;

namespace ps::python {

namespace {

// The keyword arguments: the command line's options spelt as Python names (--large-step-probability
// is large_step_probability), but for those whose values are lists or which differ in Python.
// Options that write files (-o, --stats, --checkpoint) are the Result's and the command line's.
const std::map<std::string, std::string>& optionNames() {
    static const std::map<std::string, std::string> names = {
        {"spp", "--spp"},
        {"time", "--time"},
        {"threads", "--threads"},
        {"seed", "--seed"},
        {"maxdepth", "--maxdepth"},
        {"integrator", "--integrator"},
        {"mis", "--mis"},
        {"light_paths", "--light-paths"},
        {"shadow_roulette", "--shadow-roulette"},
        {"light_samples", "--light-samples"},
        {"sampler", "--sampler"},
        {"adaptive", "--adaptive"},
        {"color", "--color"},
        {"aovs", "--aov"},            // a list: one --aov each
        {"crop", "--crop"},           // x0, x1, y0, y1
        {"pixelbounds", "--pixelbounds"},
        {"max_memory", "--max-memory"},
        {"chains", "--chains"},
        {"bootstrap", "--bootstrap"},
        {"large_step_probability", "--large-step-probability"},
        {"camera_step_probability", "--camera-step-probability"},
        {"sigma", "--sigma"},
        {"strategy_pilot", "--strategy-pilot"},
        {"two_stage", "--two-stage"},
        {"two_stage_black_level", "--two-stage-black-level"},
        {"mlt_mutations", "--mlt-mutations"},
        {"mlt_direct", "--mlt-direct"},
    };
    return names;
}

// The text the command line would have been given for a value (Python's own spelling: 0.1,
// 1e-05, 16).
std::string text(const py::handle& v) { return py::str(v).cast<std::string>(); }

// Parses the keyword arguments as `pathspace render` parses its command line, with the same
// checks; a bad value raises ValueError with the command line's message.
RenderArgs parseOptions(const py::kwargs& options, py::object& progress) {
    std::vector<std::string> args;
    RenderArgs parsed;
    for (const auto& [key, value] : options) {
        const std::string name = key.cast<std::string>();
        if (name == "progress") {
            progress = py::reinterpret_borrow<py::object>(value);
            continue;
        }
        if (name == "bdpt_strategies") {
            parsed.keepStrategies = value.cast<bool>();
            continue;
        }
        auto it = optionNames().find(name);
        if (it == optionNames().end()) {
            std::string known;
            for (const auto& [n, _] : optionNames()) known += n + ", ";
            throw py::type_error("render() got an unexpected keyword argument '" + name + "' (the options are " +
                                 known + "bdpt_strategies and progress)");
        }
        if (value.is_none()) continue;  // the scene's own setting, as when the option is not given
        const bool list = name == "aovs" || name == "crop" || name == "pixelbounds";
        if (list && !py::isinstance<py::str>(value) && py::isinstance<py::sequence>(value)) {
            if (name == "aovs") {
                for (const py::handle& v : value) args.insert(args.end(), {it->second, text(v)});
            } else {
                args.push_back(it->second);
                for (const py::handle& v : value) args.push_back(text(v));
            }
        } else {
            args.insert(args.end(), {it->second, text(value)});
        }
    }
    CLI::App app;
    addRenderOptions(&app, parsed);
    refuseOptionsAsValues(&app);
    try {
        std::reverse(args.begin(), args.end());  // CLI11 reads a vector of arguments last to first
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        raiseValueError(e.what());
    }
    return parsed;
}

// One render at a time in this process: the interrupt flag and the memory limit are the
// process's.
std::mutex gRenderMutex;

}  // namespace

py::object renderScene(py::object sceneObject, SceneObject& scene, const py::kwargs& options) {
    py::object progress = py::none();
    const RenderArgs args = parseOptions(options, progress);
    const ProgressReporting reporting = chooseProgress(progress);
    // The tqdm bar is closed however the render ends (after the GIL is back).
    struct Finish {
        const ProgressReporting& r;
        ~Finish() {
            if (r.finish) r.finish();
        }
    } finish{reporting};
    auto out = std::make_shared<RenderOutput>();
    std::exception_ptr callbackError;
    {
        py::gil_scoped_release nogil;
        const std::lock_guard<std::mutex> one(gRenderMutex);
        const ScopedMemoryLimit limit(args.maxMemory.empty() ? memoryLimit() : *parseByteSize(args.maxMemory));
        RenderSetup setup;
        Scene* built = nullptr;
        {
            const HeldWarnings inFileOrder;
            built = &scene.prepare(args.spectral());
            configureRender(*built, args, setup);
        }
        RenderOptions& opts = setup.opts;
        opts.progress = reporting.stderrBar;  // the command line's bar on stderr
        opts.errorEstimate = true;            // the statistics' noise figures
        if (reporting.report)
            opts.onProgress = [&](const Progress& p) {
                py::gil_scoped_acquire gil;
                if (callbackError) return;
                try {
                    reporting.report(p);
                } catch (...) {
                    // Stops the render; raised once it has returned.
                    callbackError = std::current_exception();
                    InterruptHandlers::request();
                }
            };
        checkRenderable(*built, *setup.integrator, opts);
        {
            const InterruptHandlers interrupts{SIGINT};  // Python's own handler is back after the render
            opts.cancel = InterruptHandlers::flag();
            out->result = render(*built, *setup.integrator, opts);
            out->interrupted = InterruptHandlers::interrupted() && !callbackError;
        }
        if (setup.bdpt) out->strategies = setup.bdpt->strategyImages()->images(out->result.lightPaths);
        completeResult(*built, out->result);
        out->stats = renderStatistics(*built, args, setup, out->result, out->result.stats, scene.file(), {},
                                      out->interrupted)
                         .dump();
    }
    if (callbackError) std::rethrow_exception(callbackError);
    py::object result = py::cast(out);
    sceneObject.attr("last_result") = result;
    if (out->interrupted) {
        py::object error = py::reinterpret_borrow<py::object>(PyExc_KeyboardInterrupt)(
            "render interrupted: the image so far is in the exception's .result (and the scene's .last_result)");
        error.attr("result") = result;
        PyErr_SetObject(PyExc_KeyboardInterrupt, error.ptr());
        throw py::error_already_set();
    }
    return result;
}

}  // namespace ps::python
