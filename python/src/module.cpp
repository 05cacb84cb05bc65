// glint._glint: the module, its exceptions, and loading (docs/python.md).

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <exception>
#include <string_view>
#include <utility>

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
    py::object error = py::reinterpret_borrow<py::object>(gSceneError)(pythonWords(e.what()));
    error.attr("file") = d.loc.file.empty() ? py::object(py::none()) : py::str(d.loc.file);
    error.attr("line") = d.loc.line;
    error.attr("column") = d.loc.column;
    error.attr("message") = pythonWords(d.message);
    PyErr_SetObject(gSceneError, error.ptr());
}

std::shared_ptr<LoadedScene> load(const std::string& path, const std::vector<std::string>& args) {
    cli::Options options = parseOptions(args, {});
    options.scene = path;
    return std::make_shared<LoadedScene>(std::move(options), nullptr);
}

}  // namespace

std::string pythonWords(const std::string& message) {
    // The flags, by what they are as keyword arguments.
    static const std::pair<std::string_view, std::string_view> kFlags[] = {
        {"lenient", "lenient=True"},
        {"no-denoise", "denoise=False"},
        {"denoise", "denoise=True"},
        {"no-srgb", "srgb=False"},
        {"srgb", "srgb=True"}};
    auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    std::string out;
    for (size_t i = 0; i < message.size();) {
        const bool starts = message.compare(i, 2, "--") == 0 && i + 2 < message.size() &&
                            std::islower(static_cast<unsigned char>(message[i + 2])) &&
                            (i == 0 || (!word(message[i - 1]) && message[i - 1] != '-'));
        if (!starts) {
            out += message[i++];
            continue;
        }
        size_t end = i + 2;
        while (end < message.size() &&
               (std::islower(static_cast<unsigned char>(message[end])) ||
                std::isdigit(static_cast<unsigned char>(message[end])) || message[end] == '-'))
            ++end;
        std::string name = message.substr(i + 2, end - i - 2);
        std::string python = name;
        std::replace(python.begin(), python.end(), '-', '_');
        if (end < message.size() && message[end] == ':') {
            out += python;  // "--spp: must be ..." names the option: "spp: must be ..."
        } else {
            std::string_view flag;
            for (const auto& [n, f] : kFlags)
                if (n == name) flag = f;
            out += flag.empty() ? python + "=" : std::string(flag);
        }
        i = end;
    }
    return out;
}

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
        if (PyErr_WarnEx(gSceneWarning, pythonWords(w.format("warning")).c_str(), 2) != 0)
            throw py::error_already_set();
    for (const std::string& w : optionWarnings)
        if (PyErr_WarnEx(gSceneWarning, pythonWords(w).c_str(), 2) != 0)
            throw py::error_already_set();
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
    m.attr("__version__") = GLINT_VERSION;
    m.attr("SceneError") = py::handle(gSceneError);
    m.attr("RenderError") = py::handle(gRenderError);
    m.attr("SceneWarning") = py::handle(gSceneWarning);

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const glint::SceneError& e) {
            raiseSceneError(e);
        } catch (const glint::cli::UsageError& e) {
            PyErr_SetString(PyExc_ValueError, pythonWords(e.what()).c_str());
        } catch (const glint::BuildError& e) {
            PyErr_SetString(PyExc_ValueError, pythonWords(e.what()).c_str());
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
