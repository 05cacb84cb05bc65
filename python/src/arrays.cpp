// NumPy arrays in and out: meshes and environment maps made of arrays, and images written or
// encoded as the command line writes them (docs/python.md).

#include <cmath>
#include <cstdint>
#include <limits>

#include "glint/denoise/film_denoise.h"
#include "glint/io/image/image_io.h"
#include "glint/scene/environment.h"
#include "glint/scene/mesh.h"
#include "glint/scene/model.h"
#include "glint_python.h"

namespace glint::python {
namespace {

/// What Python prints for `h` (a dtype, a shape).
std::string text(const py::handle& h) { return py::str(h).cast<std::string>(); }

/// Checks that `a` is a C-contiguous array of `columns` columns (a flat one of a multiple of
/// `columns` when `flat`); returns its rows.
size_t checkRows(const py::array& a, const char* what, py::ssize_t columns, bool flat = false) {
    if (!(a.flags() & py::array::c_style))
        throw py::value_error(std::string(what) +
                              ": the array is not C-contiguous (numpy.ascontiguousarray makes "
                              "one that is)");
    if (a.ndim() == 2 && a.shape(1) == columns) return static_cast<size_t>(a.shape(0));
    if (flat && a.ndim() == 1 && a.shape(0) % columns == 0)
        return static_cast<size_t>(a.shape(0) / columns);
    throw py::value_error(std::string(what) + ": expected an array of shape (N, " +
                          std::to_string(columns) + ")" + (flat ? " or (3N,)" : "") +
                          ", got one of shape " + text(a.attr("shape")));
}

bool isFloat(const py::array& a) {
    return a.dtype().is(py::dtype::of<float>()) || a.dtype().is(py::dtype::of<double>());
}

/// Rows of `columns` floats from a float32 or float64 array, each finite (else a ValueError
/// naming the row), passed to `put(row, values)`.
template <typename Put>
void readFloats(const py::array& a, const char* what, py::ssize_t columns, size_t rows, Put put) {
    if (!isFloat(a))
        throw py::type_error(std::string(what) + ": expected float32 or float64 values, got " +
                             text(a.dtype()));
    const bool single = a.dtype().is(py::dtype::of<float>());
    const auto* f = static_cast<const float*>(a.data());
    const auto* d = static_cast<const double*>(a.data());
    float v[4] = {};
    for (size_t i = 0; i < rows; ++i) {
        for (py::ssize_t c = 0; c < columns; ++c) {
            const size_t k = i * static_cast<size_t>(columns) + static_cast<size_t>(c);
            const double x = single ? static_cast<double>(f[k]) : d[k];
            if (!std::isfinite(x) ||
                std::abs(x) > static_cast<double>(std::numeric_limits<float>::max()))
                throw py::value_error(std::string(what) + ": row " + std::to_string(i) +
                                      " is not finite (NaN, infinite or beyond float range)");
            v[c] = static_cast<float>(x);
        }
        put(i, v);
    }
}

/// A triangle mesh made of arrays, in its own space: placed by glint.Scene.mesh.
struct ArrayMesh {
    std::shared_ptr<const Model> model;
    size_t vertices = 0, triangles = 0;
};

ArrayMesh makeMesh(const py::array& positions, const py::array& indices, const py::object& normals,
                   const py::object& uvs, const std::string& name) {
    MeshData mesh;
    mesh.name = name;
    const size_t n = checkRows(positions, "positions", 3);
    if (n == 0) throw py::value_error("positions: the mesh has no vertices");
    if (n > std::numeric_limits<uint32_t>::max() - 1)
        throw py::value_error("positions: more than 2^32 - 2 vertices");
    mesh.positions.resize(n);
    readFloats(positions, "positions", 3, n, [&](size_t i, const float* v) {
        mesh.positions[i] = {v[0], v[1], v[2]};
    });
    // Optional attributes, one row of `columns` per vertex, into `out` by `put`.
    auto attribute = [n](const py::object& o, const char* what, py::ssize_t columns, auto& out,
                         auto put) {
        if (o.is_none()) return;
        const auto a = o.cast<py::array>();
        if (checkRows(a, what, columns) != n)
            throw py::value_error(std::string(what) + ": one per vertex expected (" +
                                  std::to_string(n) + "), got " + std::to_string(a.shape(0)));
        out.resize(n);
        readFloats(a, what, columns, n, [&](size_t i, const float* v) { out[i] = put(v); });
    };
    attribute(normals, "normals", 3, mesh.normals, [](const float* v) {
        return Vec3f{v[0], v[1], v[2]};
    });
    attribute(uvs, "uvs", 2, mesh.uvs, [](const float* v) { return TexCoord{v[0], v[1]}; });
    const size_t t = checkRows(indices, "indices", 3, true);
    const py::dtype dt = indices.dtype();
    if (dt.kind() != 'i' && dt.kind() != 'u')
        throw py::type_error("indices: expected integers, got " + text(dt));
    const int bytes = static_cast<int>(dt.itemsize());
    const bool isSigned = dt.kind() == 'i';
    const auto* raw = static_cast<const unsigned char*>(indices.data());
    auto index = [&](size_t k) -> long long {
        const unsigned char* p = raw + k * static_cast<size_t>(bytes);
        switch (bytes) {
            case 1:
                return isSigned ? *reinterpret_cast<const int8_t*>(p) : *p;
            case 2:
                return isSigned ? *reinterpret_cast<const int16_t*>(p)
                                : *reinterpret_cast<const uint16_t*>(p);
            case 4:
                return isSigned ? *reinterpret_cast<const int32_t*>(p)
                                : *reinterpret_cast<const uint32_t*>(p);
            default: {
                if (isSigned) return *reinterpret_cast<const int64_t*>(p);
                const uint64_t u = *reinterpret_cast<const uint64_t*>(p);
                return u > static_cast<uint64_t>(std::numeric_limits<long long>::max())
                           ? -1
                           : static_cast<long long>(u);
            }
        }
    };
    mesh.triangles.resize(t);
    for (size_t i = 0; i < t; ++i) {
        MeshData::Triangle& tri = mesh.triangles[i];
        for (size_t c = 0; c < 3; ++c) {
            const long long v = index(3 * i + c);
            if (v < 0 || static_cast<unsigned long long>(v) >= n)
                throw py::value_error("indices: triangle " + std::to_string(i) + " names vertex " +
                                      std::to_string(v) + ", outside 0 to " +
                                      std::to_string(n - 1));
            MeshData::Corner& corner = tri.corners[c];
            corner.position = static_cast<uint32_t>(v);
            if (!mesh.normals.empty()) corner.normal = corner.position;
            if (!mesh.uvs.empty()) corner.uv = corner.position;
        }
    }
    mesh.normalTriangles = mesh.normals.empty() ? 0 : t;
    mesh.uvTriangles = mesh.uvs.empty() ? 0 : t;
    ArrayMesh out;
    out.vertices = n;
    out.triangles = t;
    out.model = std::make_shared<const Model>(singleMeshModel(std::move(mesh)));
    return out;
}

/// `image` (rows x columns x 3, any real dtype) as a film; `frame`'s film when the image is that
/// frame's, unchanged (float32 of each of its values), so that it encodes to the same bytes.
const Film& filmOf(const py::array& image, const std::shared_ptr<Frame>& frame, Film& scratch) {
    if (image.ndim() != 3 || image.shape(2) != 3 || image.shape(0) < 1 || image.shape(1) < 1)
        throw py::value_error("image: expected an array of shape (height, width, 3), got " +
                              text(image.attr("shape")));
    if (image.dtype().kind() != 'f' && image.dtype().kind() != 'i' && image.dtype().kind() != 'u')
        throw py::type_error("image: expected real numbers, got " + text(image.dtype()));
    const auto h = static_cast<int>(image.shape(0)), w = static_cast<int>(image.shape(1));
    if (frame && frame->film.width() == w && frame->film.height() == h &&
        image.dtype().is(py::dtype::of<float>()) && (image.flags() & py::array::c_style)) {
        const auto* f = static_cast<const float*>(image.data());
        const std::vector<Vec3>& px = frame->film.pixels();
        bool same = true;
        for (size_t i = 0; i < px.size() && same; ++i)
            same = f[3 * i] == static_cast<float>(px[i].x) &&
                   f[3 * i + 1] == static_cast<float>(px[i].y) &&
                   f[3 * i + 2] == static_cast<float>(px[i].z);
        if (same) return frame->film;
    }
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(image);
    if (!d) throw py::error_already_set();
    std::vector<Vec3> pixels(static_cast<size_t>(w) * static_cast<size_t>(h));
    const double* v = d.data();
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    scratch = Film(w, h, std::move(pixels));
    return scratch;
}

/// The passes `passes` names (albedo, normal, depth, variance: arrays of the image's size). Files
/// hold them as float32, so the arrays give the rendered passes' values exactly.
RenderPasses passesOf(const py::dict& passes, int w, int h, AovSelection& which) {
    RenderPasses out;
    if (passes.empty()) return out;
    out.width = w;
    out.height = h;
    const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
    for (auto item : passes) {
        const std::string name = item.first.cast<std::string>();
        auto a =
            py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(item.second);
        if (!a) throw py::error_already_set();
        const bool scalar = name == "depth";
        if (a.ndim() != (scalar ? 2 : 3) || a.shape(0) != h || a.shape(1) != w ||
            (!scalar && a.shape(2) != 3))
            throw py::value_error("passes['" + name + "']: expected shape (" + std::to_string(h) +
                                  ", " + std::to_string(w) + (scalar ? ")" : ", 3)"));
        const double* v = a.data();
        if (scalar) {
            out.depth.assign(v, v + n);
            which.depth = true;
            continue;
        }
        std::vector<Vec3>* target = name == "albedo"           ? &out.albedo
                                    : name == "normal"         ? &out.normal
                                    : name == "variance"       ? &out.variance
                                    : name == "albedoVariance" ? &out.albedoVariance
                                                               : nullptr;
        if (!target)
            throw py::value_error("passes: unknown pass '" + name +
                                  "' (albedo, normal, depth, variance, albedoVariance)");
        target->resize(n);
        for (size_t i = 0; i < n; ++i) (*target)[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
        // The albedo's variance is written with the variance and the albedo (exr.h).
        if (name != "albedoVariance")
            (name == "albedo"   ? which.albedo
             : name == "normal" ? which.normal
                                : which.variance) = true;
    }
    return out;
}

DisplayTransform displayOf(double exposure, bool srgb, const std::string& tonemap) {
    if (!std::isfinite(exposure) || exposure < -64 || exposure > 64)
        throw py::value_error("exposure: must be -64 to 64");
    std::optional<ToneMap> t = toneMapNamed(tonemap);
    if (!t) throw py::value_error("tonemap: neutral, aces or clamp, got '" + tonemap + "'");
    return {exposure, srgb, *t};
}

/// The image encoded as `format` would write it (8-bit formats through `display`).
std::string encode(ImageFormat format, const py::array& image, const py::dict& passes,
                   const DisplayTransform& display, const std::shared_ptr<Frame>& frame) {
    Film scratch;
    const Film& film = filmOf(image, frame, scratch);
    AovSelection which;
    RenderPasses p = passesOf(passes, film.width(), film.height(), which);
    py::gil_scoped_release nogil;
    return encodeImage(film, format, display, p.empty() ? nullptr : &p, which);
}

}  // namespace

void bindArrays(py::module_& m) {
    py::class_<Frame, std::shared_ptr<Frame>>(m, "Frame",
                                              "A rendered image at the film's full precision.");

    py::class_<ArrayMesh>(m, "Mesh")
        .def(py::init(&makeMesh), py::arg("positions"), py::arg("indices"),
             py::arg("normals") = py::none(), py::arg("uvs") = py::none(), py::arg("name") = "mesh")
        .def_readonly("vertices", &ArrayMesh::vertices)
        .def_readonly("triangles", &ArrayMesh::triangles);

    m.def(
        "from_text",
        [](const std::string& text, const std::string& name, const py::dict& meshes,
           const std::vector<std::string>& args) {
            cli::SceneText source;
            source.text = text;
            source.name = name;
            for (auto item : meshes)
                source.models[item.first.cast<std::string>()] =
                    item.second.cast<const ArrayMesh&>().model;
            cli::Options options = parseOptions(args, {});
            return std::make_shared<LoadedScene>(std::move(options), &source);
        },
        py::arg("text"), py::arg("name"), py::arg("meshes"), py::arg("args"));

    m.def(
        "set_environment",
        [](LoadedScene& scene, const py::object& rgb, double scale, double rotation) {
            std::shared_ptr<const EnvironmentMap> map;
            if (!rgb.is_none()) {
                const auto a = rgb.cast<py::array>();
                if (a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) < 1 || a.shape(1) < 1)
                    throw py::value_error(
                        "environment: expected an array of shape (height, width, 3), got " +
                        text(a.attr("shape")));
                const auto h = static_cast<int>(a.shape(0)), w = static_cast<int>(a.shape(1));
                if (!(a.flags() & py::array::c_style))
                    throw py::value_error("environment: the array is not C-contiguous");
                std::vector<float> values(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
                readFloats(a, "environment", 3, static_cast<size_t>(w) * static_cast<size_t>(h),
                           [&](size_t i, const float* v) {
                               if (v[0] < 0 || v[1] < 0 || v[2] < 0)
                                   throw py::value_error("environment: pixel " + std::to_string(i) +
                                                         " is negative");
                               values[3 * i] = v[0];
                               values[3 * i + 1] = v[1];
                               values[3 * i + 2] = v[2];
                           });
                try {
                    map = std::make_shared<const EnvironmentMap>(w, h, std::move(values), scale,
                                                                 rotation);
                } catch (const std::invalid_argument& e) {
                    throw py::value_error(std::string("environment: ") + e.what());
                }
            }
            py::gil_scoped_release nogil;
            std::lock_guard<std::mutex> lock(scene.mutex);
            scene.prepared.scene->environment = std::move(map);
        },
        py::arg("scene"), py::arg("rgb"), py::arg("scale") = 1.0, py::arg("rotation") = 0.0);

    m.def(
        "encode",
        [](const std::string& format, const py::array& image, const py::dict& passes,
           double exposure, bool srgb, const std::string& tonemap,
           const std::shared_ptr<Frame>& frame) {
            std::optional<ImageFormat> f = imageFormatFor("image." + format);
            if (!f) throw py::value_error("format: png, ppm, pfm or exr, got '" + format + "'");
            return py::bytes(encode(*f, image, passes, displayOf(exposure, srgb, tonemap), frame));
        },
        py::arg("format"), py::arg("image"), py::arg("passes"), py::arg("exposure"),
        py::arg("srgb"), py::arg("tonemap"), py::arg("frame") = nullptr);

    m.def(
        "write",
        [](const std::string& path, const py::array& image, const py::dict& passes, double exposure,
           bool srgb, const std::string& tonemap, const std::shared_ptr<Frame>& frame) {
            if (!imageFormatFor(path))
                throw py::value_error("cannot write '" + path + "': unknown image format (use " +
                                      kImageExtensions + ")");
            const DisplayTransform display = displayOf(exposure, srgb, tonemap);
            Film scratch;
            const Film& film = filmOf(image, frame, scratch);
            AovSelection which;
            RenderPasses p = passesOf(passes, film.width(), film.height(), which);
            if (which.any() && imageFormatFor(path) != ImageFormat::Exr)
                throw py::value_error("passes are written as layers of an OpenEXR file: '" + path +
                                      "' is not an .exr file");
            py::gil_scoped_release nogil;
            writeImage(path, film, display, p.empty() ? nullptr : &p, which);
        },
        py::arg("path"), py::arg("image"), py::arg("passes"), py::arg("exposure"), py::arg("srgb"),
        py::arg("tonemap"), py::arg("frame") = nullptr);
    m.def(
        "denoise",
        [](const py::array& image, const py::dict& passes, const std::string& denoiser,
           const std::string& quality, int threads) {
            FilmDenoiseOptions options;
            try {
                options.denoiser = denoiserNamed(denoiser);
                options.quality = denoiseQualityNamed(quality);
            } catch (const std::invalid_argument& e) {
                throw py::value_error(e.what());
            }
            if (threads < 0) throw py::value_error("threads: must be 0 (every core) or more");
            Film scratch;
            const Film& film = filmOf(image, nullptr, scratch);
            AovSelection which;
            RenderPasses p = passesOf(passes, film.width(), film.height(), which);
            FilmDenoiseReport report;
            Film out;
            {
                py::gil_scoped_release nogil;
                ThreadPool pool(threads);
                out = denoiseFilm(film, p, pool, options, &report);
            }
            return py::make_tuple(imageArray(out.pixels(), out.width(), out.height()),
                                  report.method);
        },
        py::arg("image"), py::arg("passes"), py::arg("denoiser"), py::arg("quality"),
        py::arg("threads"));
}

}  // namespace glint::python
