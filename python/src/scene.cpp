// glint._glint.LoadedScene: a scene loaded as the command line loads it, rendered as it renders
// (cli::renderPlanned), with the GIL released, Ctrl-C and a progress callback.

#include <atomic>
#include <cmath>

#include "glint/render/renderer.h"
#include "glint/scene/model.h"
#include "glint_python.h"

namespace glint::python {

py::array_t<float> imageArray(const std::vector<Vec3>& pixels, int width, int height) {
    py::array_t<float> a(
        {static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width), py::ssize_t{3}});
    float* out = a.mutable_data();
    for (size_t i = 0; i < pixels.size(); ++i) {
        out[3 * i] = static_cast<float>(pixels[i].x);
        out[3 * i + 1] = static_cast<float>(pixels[i].y);
        out[3 * i + 2] = static_cast<float>(pixels[i].z);
    }
    return a;
}

namespace {

py::array_t<float> depthArray(const std::vector<double>& depth, int width, int height) {
    py::array_t<float> a({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width)});
    float* out = a.mutable_data();
    for (size_t i = 0; i < depth.size(); ++i) out[i] = static_cast<float>(depth[i]);
    return a;
}

py::dict displayDict(const DisplayTransform& d) {
    py::dict out;
    out["exposure"] = d.exposure;
    out["srgb"] = d.srgb;
    out["tonemap"] = std::string(toneMapName(d.toneMap));
    return out;
}

/// A camera as Python sees it: a dict of eye, target, up, fov, aperture and focus.
py::dict cameraDict(const CameraSpec& c) {
    py::dict out;
    out["eye"] = py::make_tuple(c.eye.x, c.eye.y, c.eye.z);
    out["target"] = py::make_tuple(c.center.x, c.center.y, c.center.z);
    out["up"] = py::make_tuple(c.up.x, c.up.y, c.up.z);
    out["fov"] = c.fovyDegrees;
    out["aperture"] = c.apertureRadius;
    out["focus"] = c.focusDistance;
    return out;
}

Vec3 vec3Of(const py::handle& h, const char* what) {
    std::vector<double> v;
    try {
        v = h.cast<std::vector<double>>();
    } catch (const py::cast_error&) {
        throw py::type_error(std::string("camera ") + what + ": expected 3 numbers");
    }
    if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
        throw py::value_error(std::string("camera ") + what + ": expected 3 finite numbers");
    return {v[0], v[1], v[2]};
}

/// Checks a camera as the scene format does (eye != target, up not along the view, fov in
/// (0, 180), lens >= 0).
CameraSpec cameraOf(const CameraSpec& base, const py::dict& d) {
    CameraSpec c = base;
    for (auto item : d) {
        const std::string key = item.first.cast<std::string>();
        if (key == "eye")
            c.eye = vec3Of(item.second, "eye");
        else if (key == "target")
            c.center = vec3Of(item.second, "target");
        else if (key == "up")
            c.up = vec3Of(item.second, "up");
        else if (key == "fov")
            c.fovyDegrees = item.second.cast<double>();
        else if (key == "aperture")
            c.apertureRadius = item.second.cast<double>();
        else if (key == "focus")
            c.focusDistance = item.second.cast<double>();
        else
            throw py::type_error("camera: unknown key '" + key +
                                 "' (eye, target, up, fov, aperture, focus)");
    }
    if (!(c.fovyDegrees > 0 && c.fovyDegrees < 180))
        throw py::value_error("camera fov: must be between 0 and 180 degrees");
    if (!(c.apertureRadius >= 0 && std::isfinite(c.apertureRadius)) ||
        !(c.focusDistance >= 0 && std::isfinite(c.focusDistance)))
        throw py::value_error("camera aperture and focus: must be finite and >= 0");
    const Vec3 view = c.center - c.eye;
    if (length(view) == 0) throw py::value_error("camera: eye and target are the same point");
    if (length(cross(view, c.up)) <= 1e-12 * length(view) * length(c.up))
        throw py::value_error("camera: up is zero or along the view direction");
    return c;
}

}  // namespace

LoadedScene::LoadedScene(cli::Options opts, const cli::SceneText* source)
    : options(std::move(opts)) {
    std::vector<Diagnostic> warnings;
    {
        py::gil_scoped_release nogil;
        cli::prepareScene(options, prepared, warnings, nullptr, source);
    }
    warn(warnings, prepared.optionWarnings);
}

py::tuple LoadedScene::render(const std::vector<std::string>& args, const py::object& progress) {
    const cli::Options o = parseOptions(args, options);
    AovSelection aovs;
    if (!o.aov.empty()) parseAovList(o.aov, aovs);  // checked with the options
    std::atomic<bool> cancel{false};
    bool failed = false;  // a Python exception (KeyboardInterrupt, the callback's) is pending
    cli::Rendered r;
    DisplayTransform display;
    {
        py::gil_scoped_release nogil;
        std::lock_guard<std::mutex> lock(mutex);
        Scene& scene = *prepared.scene;
        cli::applyRenderSettings(o, scene);
        display = cli::displayFor(o, scene);
        const cli::SamplingPlan plan = cli::planSampling(o, prepared, false, true);
        if (!pool_ || poolThreads_ != o.threads) {
            pool_.reset();
            pool_ = std::make_unique<ThreadPool>(o.threads);
            poolThreads_ = o.threads;
        }
        RenderOptions ro;
        ro.pool = pool_.get();
        ro.seed = o.seed;
        ro.cancel = &cancel;
        // About ten times a second, on this thread: Ctrl-C, then the caller's callback.
        ro.onProgress = [&](const RenderProgress& p) {
            if (failed) return;
            py::gil_scoped_acquire gil;
            if (PyErr_CheckSignals() != 0) {
                failed = true;
                cancel = true;
                return;
            }
            if (progress.is_none()) return;
            try {
                progress(p.fraction(), p.seconds);
            } catch (py::error_already_set& e) {
                e.restore();
                failed = true;
                cancel = true;
            }
        };
        r = cli::renderPlanned(o, prepared, plan, ro, aovs.any());
    }
    if (failed) throw py::error_already_set();
    if (!r.result.complete || r.result.stoppedEarly) {
        // Cancelled without a Python error pending: only a signal handled elsewhere does that.
        PyErr_SetString(PyExc_KeyboardInterrupt, "render stopped");
        throw py::error_already_set();
    }

    RenderResult& res = r.result;
    const int w = res.film.width(), h = res.film.height();
    py::array_t<float> image = imageArray(res.film.pixels(), w, h);
    py::dict passes;
    if (aovs.albedo) passes["albedo"] = imageArray(res.aovs.albedo, w, h);
    if (aovs.normal) passes["normal"] = imageArray(res.aovs.normal, w, h);
    if (aovs.depth) passes["depth"] = depthArray(res.aovs.depth, w, h);
    if (aovs.variance) passes["variance"] = imageArray(res.aovs.variance, w, h);
    // Written beside the variance when the albedo is there too (exr.h), so here too.
    if (aovs.variance && aovs.albedo)
        passes["albedoVariance"] = imageArray(res.aovs.albedoVariance, w, h);
    py::dict info;
    info["spp"] = res.samplesPerPixel;
    info["mean_spp"] = res.meanSamplesPerPixel > 0 ? res.meanSamplesPerPixel
                                                   : static_cast<double>(res.samplesPerPixel);
    info["converged"] = res.converged;
    info["seconds"] = res.seconds;
    info["build_seconds"] = r.buildSeconds;
    info["denoise_seconds"] = r.denoiseSeconds;
    info["denoised"] = r.denoiseSeconds > 0;
    info["denoiser"] = r.denoiseSeconds > 0 ? py::object(py::str(r.denoised.method)) : py::none();
    info["rays"] = res.rays.total();
    info["display"] = displayDict(display);
    auto frame = std::make_shared<Frame>();
    frame->film = std::move(res.film);
    return py::make_tuple(image, passes, info, frame);
}

void bindScene(py::module_& m) {
    py::class_<LoadedScene, std::shared_ptr<LoadedScene>>(m, "LoadedScene")
        .def("render", &LoadedScene::render, py::arg("args"), py::arg("progress") = py::none())
        .def_property(
            "size",
            [](LoadedScene& s) {
                return py::make_tuple(s.prepared.scene->width, s.prepared.scene->height);
            },
            [](LoadedScene& s, std::pair<int, int> size) {
                if (size.first < 1 || size.second < 1 || size.first > kMaxImageSide ||
                    size.second > kMaxImageSide ||
                    static_cast<long long>(size.first) * size.second > kMaxImagePixels)
                    throw py::value_error("size: each side 1 to " + std::to_string(kMaxImageSide) +
                                          " pixels, at most " + std::to_string(kMaxImagePixels) +
                                          " in all");
                py::gil_scoped_release nogil;
                std::lock_guard<std::mutex> lock(s.mutex);
                s.prepared.scene->width = size.first;
                s.prepared.scene->height = size.second;
            })
        .def_property(
            "camera",
            [](LoadedScene& s) -> py::object {
                const Scene& scene = *s.prepared.scene;
                if (!scene.camera) return py::none();
                return cameraDict(*scene.camera);
            },
            [](LoadedScene& s, const py::dict& d) {
                const Scene& scene = *s.prepared.scene;
                CameraSpec c = cameraOf(scene.camera.value_or(CameraSpec{}), d);
                py::gil_scoped_release nogil;
                std::lock_guard<std::mutex> lock(s.mutex);
                s.prepared.scene->camera = c;
                s.prepared.scene->cameraMotion.clear();  // the one given, still
            })
        .def_property_readonly("integrator",
                               [](LoadedScene& s) { return s.prepared.scene->integrator; })
        .def_property_readonly("spp", [](LoadedScene& s) { return s.prepared.scene->spp; })
        .def_property_readonly("model", [](LoadedScene& s) { return s.prepared.model; })
        .def_property_readonly("note", [](LoadedScene& s) { return s.prepared.note; })
        .def_property_readonly("output", [](LoadedScene& s) { return s.prepared.output; })
        .def_property_readonly("display",
                               [](LoadedScene& s) { return displayDict(s.prepared.display); })
        .def_property_readonly("lights",
                               [](LoadedScene& s) { return s.prepared.scene->lights.size(); })
        .def_property_readonly(
            "triangles",
            [](LoadedScene& s) { return s.prepared.scene->primitives.triangleCount(); })
        .def_property_readonly("extensions",
                               [](LoadedScene& s) {
                                   py::dict out;
                                   for (const FormatExtension& e : s.prepared.extensions)
                                       out[py::str(e.name)] = e.support;
                                   return out;
                               })
        .def_property_readonly("animations", [](LoadedScene& s) {
            py::list out;
            for (const ModelAnimation& a : s.prepared.animations) {
                py::dict d;
                d["name"] = a.name;
                d["start"] = a.start;
                d["end"] = a.end;
                d["channels"] = a.channels;
                out.append(d);
            }
            return out;
        });
}

}  // namespace glint::python
