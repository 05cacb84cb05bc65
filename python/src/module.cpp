// glint._glint: the module, its exceptions, and loading (docs/python.md).

#include <CLI/CLI.hpp>
#include <exception>

#include "glint/core/error.h"
#include "glint/scene/scene_builder.h"
#include "glint_python.h"
#include "options.h"

namespace glint::python {
namespace {

// The module's exception and warning classes, made once when it is imported.
PyObject* gSceneError = nullptr;
PyObject* gRenderError = nullptr;
PyObject* gSceneWarning = nullptr;

/// Raises `e` as glint.SceneError, with its place in the file as attributes.
void raiseSceneError(const SceneError& e) {
    const Diagnostic& d = e.diagnostic();
    py::object error = py::reinterpret_borrow<py::object>(gSceneError)(e.what());
    error.attr("file") = d.loc.file.empty() ? py::object(py::none()) : py::str(d.loc.file);
    error.attr("line") = d.loc.line;
    error.attr("column") = d.loc.column;
    error.attr("message") = d.message;
    PyErr_SetObject(gSceneError, error.ptr());
}

std::shared_ptr<LoadedScene> load(const std::string& path, const std::vector<std::string>& args) {
    cli::Options options = parseOptions(args, {});
    options.scene = path;
    return std::make_shared<LoadedScene>(std::move(options), nullptr);
}

}  // namespace

cli::Options parseOptions(const std::vector<std::string>& args, cli::Options base) {
    CLI::App app{"glint", "glint"};
    cli::Options parsed = base;
    cli::addOptions(app, parsed);
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them so
    try {
        app.parse(reversed);
    } catch (const CLI::ParseError& e) {
        throw cli::UsageError(e.what());
    }
    return parsed;
}

void warn(const std::vector<Diagnostic>& warnings, const std::vector<std::string>& optionWarnings) {
    for (const Diagnostic& w : warnings)
        if (PyErr_WarnEx(gSceneWarning, w.format("warning").c_str(), 2) != 0)
            throw py::error_already_set();
    for (const std::string& w : optionWarnings)
        if (PyErr_WarnEx(gSceneWarning, w.c_str(), 2) != 0) throw py::error_already_set();
}

}  // namespace glint::python

PYBIND11_MODULE(_glint, m) {
    namespace py = pybind11;
    using namespace glint::python;
    m.doc() = "Glint's renderer, as the glint package uses it (docs/python.md).";

    gSceneError = PyErr_NewExceptionWithDoc(
        "glint.SceneError",
        "A scene, model or option that Glint cannot use. Attributes: file, line and column of "
        "the problem (line and column 0 when unknown), and message without the place.",
        PyExc_ValueError, nullptr);
    gRenderError = PyErr_NewExceptionWithDoc(
        "glint.RenderError", "Rendering or writing an image failed (not the scene's fault).",
        PyExc_RuntimeError, nullptr);
    gSceneWarning = PyErr_NewExceptionWithDoc(
        "glint.SceneWarning",
        "What the command line prints as a warning: a scene line it skipped or an option that "
        "does not apply.",
        PyExc_UserWarning, nullptr);
    m.attr("SceneError") = py::handle(gSceneError);
    m.attr("RenderError") = py::handle(gRenderError);
    m.attr("SceneWarning") = py::handle(gSceneWarning);

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const glint::SceneError& e) {
            raiseSceneError(e);
        } catch (const glint::cli::UsageError& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const glint::BuildError& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const glint::RenderError& e) {
            PyErr_SetString(gRenderError, e.what());
        }
    });

    m.def("load", &load, py::arg("path"), py::arg("args"),
          "Loads a scene or model file with the command line's options (as arguments).");
    m.def(
        "option_names",
        [] {
            CLI::App app{"glint", "glint"};
            glint::cli::Options options;
            glint::cli::addOptions(app, options);
            std::vector<std::string> names;
            for (const CLI::Option* o : app.get_options())
                for (const std::string& n : o->get_lnames()) names.push_back(n);
            return names;
        },
        "The command line's long option names (without the dashes).");
    bindScene(m);
    bindArrays(m);
}
