#pragma once
// The Python module's C++ half, `glint._glint` (docs/python.md). The package's __init__.py turns
// keyword arguments into the command line's options and wraps what this returns; everything
// that renders goes through apps/cli.h, as the glint program's renders do, so that both give the
// same pixels for the same options.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "cli.h"
#include "glint/core/parallel.h"
#include "glint/render/film/film.h"

namespace glint::python {

namespace py = pybind11;

/// `message` with the command line's option names as Python spells them: --maxdepth is
/// maxdepth=, --spp: is spp:, --lenient is lenient=True, --no-denoise is denoise=False. Every
/// message the module raises or warns with goes through it.
std::string pythonWords(const std::string& message);

/// `base` with the options `args` give, parsed as the glint command line parses them (the same
/// names, checks and messages). Throws cli::UsageError.
cli::Options parseOptions(const std::vector<std::string>& args, cli::Options base);

/// Raises each warning as a Python warning (glint.SceneWarning), as the command line prints it.
void warn(const std::vector<Diagnostic>& warnings, const std::vector<std::string>& optionWarnings);

/// A rendered image at the film's full precision, kept beside the float32 array NumPy holds: an
/// image written or shown unchanged is encoded from it, so that its file has the command line's
/// bytes (8-bit levels are decided at the film's precision; float files hold float32 anyway).
struct Frame {
    Film film;
};

/// A scene loaded from a file or made by glint.Scene, ready to render again and again.
class LoadedScene {
  public:
    LoadedScene(cli::Options options, const cli::SceneText* source);

    /// Renders with the load options changed by `args` (the render keyword arguments). Returns
    /// (image, passes, info, frame). `progress`: None or a callable(fraction, seconds).
    py::tuple render(const std::vector<std::string>& args, const py::object& progress);

    cli::Options options;  ///< As loaded.
    cli::Prepared prepared;
    std::mutex mutex;  ///< Held while the scene renders or changes.

  private:
    std::unique_ptr<ThreadPool> pool_;
    int poolThreads_ = -1;
};

void bindArrays(py::module_& m);
void bindScene(py::module_& m);

/// The film's pixels as a float32 array of rows x columns x 3 (the only copy: NumPy's).
py::array_t<float> imageArray(const std::vector<Vec3>& pixels, int width, int height);

}  // namespace glint::python
