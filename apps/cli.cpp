#include "cli.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "demo_scene.h"
#include "glint/core/error.h"
#include "glint/core/parallel.h"
#include "glint/denoise/film_denoise.h"
#include "glint/denoise/network_denoise.h"
#include "glint/io/course/course_loader.h"
#include "glint/io/image/environment_io.h"
#include "glint/io/image/image_io.h"
#include "glint/io/registry.h"
#include "glint/render/adaptive.h"
#include "glint/render/film/piece.h"
#include "glint/render/integrators/integrator.h"
#include "glint/render/progressive.h"
#include "glint/scene/studio_environment.h"

namespace glint::cli {
namespace {

/// Parses "WxH" within the scene limits; returns what is wrong, or nothing.
std::string parseSize(const std::string& s, int& w, int& h) {
    const std::string form = "--size expects WIDTHxHEIGHT, e.g. 640x480, got '" + s + "'";
    auto x = s.find_first_of("xX");
    if (x == std::string::npos) return form;
    long long a = 0, b = 0;
    auto whole = [](const char* first, const char* last, long long& v) {
        auto [p, ec] = std::from_chars(first, last, v);
        return first != last && ec == std::errc() && p == last;
    };
    if (!whole(s.data(), s.data() + x, a) || !whole(s.data() + x + 1, s.data() + s.size(), b))
        return form;
    if (a < 1 || b < 1 || a > kMaxImageSide || b > kMaxImageSide)
        return "--size: each side must be 1 to " + std::to_string(kMaxImageSide) +
               " pixels, got '" + s + "'";
    if (a * b > kMaxImagePixels)
        return "--size: at most " + std::to_string(kMaxImagePixels) + " pixels, got '" + s + "'";
    w = static_cast<int>(a);
    h = static_cast<int>(b);
    return {};
}

/// The environment `--environment` names: the studio's, none (a null map) or a file's.
/// Throws RenderError if the file cannot be read.
std::shared_ptr<const EnvironmentMap> environmentNamed(const std::string& name) {
    if (name == "studio") return studioEnvironment();
    if (name == "none") return nullptr;
    HdrImage image = loadEnvironmentImage(name);
    return std::make_shared<const EnvironmentMap>(image.width, image.height, std::move(image.rgb));
}

}  // namespace

SamplingPlan planSampling(const Options& opt, const Prepared& prepared, bool piece,
                          bool timeBudgets) {
    const Scene& scene = *prepared.scene;
    SamplingPlan p;
    p.spp = opt.spp > 0 ? opt.spp : (scene.spp > 0 ? scene.spp : 1);
    p.maxSpp = opt.spp > 0 ? opt.spp : kAdaptiveMaxSpp;
    // The studio look only: the classic one (--integrator whitted) renders as it always did.
    p.studio = prepared.model && scene.integrator != "whitted";
    p.modelDefaults =
        p.studio && !piece && opt.spp == 0 && opt.timeBudget == 0 && opt.noiseThreshold == 0;
    p.threshold = p.modelDefaults ? kModelNoiseThreshold : opt.noiseThreshold;
    p.seconds = p.modelDefaults && timeBudgets ? kModelSeconds : opt.timeBudget;
    p.denoise = !piece && (opt.denoise != 0 ? opt.denoise > 0 : p.studio);
    return p;
}

Rendered renderPlanned(const Options& opt, Prepared& prepared, const SamplingPlan& plan,
                       RenderOptions ro, bool aovs, FrameAccel* accel) {
    using Clock = std::chrono::steady_clock;
    Scene& scene = *prepared.scene;
    Rendered out;
    if (!scene.prepared()) {
        auto t = Clock::now();
        scene.prepare({ro.pool, prepared.kernels, accel});
        out.buildSeconds = secondsSince(t);
    }
    ro.spp = plan.spp;
    ro.aovs = aovs || plan.denoise;
    out.result =
        plan.threshold > 0
            ? renderAdaptive(scene, ro, {plan.threshold, opt.minSpp, plan.maxSpp, plan.seconds})
        : opt.timeBudget > 0 ? renderForTime(scene, ro, {opt.timeBudget, opt.spp})
                             : render(scene, ro);
    if (plan.denoise && out.result.complete) {
        auto t = Clock::now();
        std::optional<ThreadPool> own;
        ThreadPool& pool = ro.pool ? *ro.pool : own.emplace(ro.threads);
        out.result.film =
            denoiseFilm(out.result.film, out.result.aovs, pool,
                        filmDenoiseOptions(opt.denoiser, opt.denoiseQuality), &out.denoised);
        out.denoiseSeconds = secondsSince(t);
    }
    return out;
}

FilmDenoiseOptions filmDenoiseOptions(const std::string& denoiser, const std::string& quality) {
    return {denoiserNamed(denoiser), denoiseQualityNamed(quality)};
}

std::string denoiserProblem(const std::string& denoiser, const std::string& quality) {
    if (denoiser != "oidn" || networkDenoiserAvailable(denoiseQualityNamed(quality))) return "";
    return "--denoiser oidn: this build of glint has no weights for the network "
           "(denoise-weights/fetch.sh fetches them; then build again); use --denoiser nlm or auto";
}

std::string darkImageWarning(const Film& film, const DisplayTransform& display) {
    const size_t n = static_cast<size_t>(film.width()) * film.height();
    if (n == 0) return "";
    double sum = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) sum += std::max(0.0, luminance(film.at(x, y)));
    const double mean = sum / static_cast<double>(n) * display.scale();
    if (!std::isfinite(mean) || mean >= 0.001) return "";
    char text[32];
    std::snprintf(text, sizeof text, "%.2g", mean);
    return std::string("the image is almost black (its mean is ") + text +
           " of white): little or no light reaches what the camera sees. Try --environment "
           "studio (light from every side), --camera none (Glint's own framing: a camera inside "
           "closed geometry, such as a sky dome, sees only its inside), lights of your own, or "
           "--exposure EV";
}

void warnNonFinite(const char* program, const FilmDenoiseReport& report) {
    if (report.nonFinite > 0)
        std::fprintf(stderr,
                     "%s: warning: %zu pixels held values that are not finite (NaN or infinity): "
                     "the denoiser took them as 0\n",
                     program, report.nonFinite);
}

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// "1 light", "2 lights".
std::string count(unsigned long long n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

/// "2 triangles, 1 sphere", then the other kinds the scene has: "1 box, 2 planes". Polygons
/// are counted as the triangles they became.
std::string depthSummary(const Scene& scene) {
    std::string text = "maxdepth " + std::to_string(scene.maxDepth), kinds;
    const BounceLimits& b = scene.bounces;
    for (auto [name, limit] : {std::pair{"diffuse", b.diffuse},
                               {"glossy", b.glossy},
                               {"transmission", b.transmission},
                               {"volume", b.volume}})
        if (limit != BounceLimits::kUnlimited)
            kinds += (kinds.empty() ? "" : ", ") + std::string(name) + " " + std::to_string(limit);
    return kinds.empty() ? text : text + " (" + kinds + ")";
}

std::string primitiveSummary(const Primitives& prims) {
    using glint::ShapeKind;
    std::string s = count(prims.triangleCount(), "triangle", "triangles") + ", " +
                    count(prims.sphereCount(), "sphere", "spheres");
    const struct {
        unsigned long long n;
        const char *one, *many;
    } kinds[] = {{prims.shapeCount(ShapeKind::Box), "box", "boxes"},
                 {prims.shapeCount(ShapeKind::Cylinder), "cylinder", "cylinders"},
                 {prims.shapeCount(ShapeKind::Cone), "cone", "cones"},
                 {prims.shapeCount(ShapeKind::Disk), "disk", "disks"},
                 {prims.instanceCount(), "mesh instance", "mesh instances"},
                 {prims.planeCount(), "plane", "planes"}};
    for (const auto& k : kinds)
        if (k.n > 0) s += ", " + count(k.n, k.one, k.many);
    return s;
}

DisplayTransform DisplayOptions::over(DisplayTransform base) const {
    if (exposure) base.exposure = *exposure;
    if (srgb != 0) base.srgb = srgb > 0;
    if (!toneMap.empty()) base.toneMap = *toneMapNamed(toneMap);
    return base;
}

int usageError(const std::string& message) {
    std::fprintf(stderr, "glint: error: %s\nRun 'glint --help' for usage.\n", message.c_str());
    return kExitUsage;
}

void printStats(const Scene& scene, double parse, double build, const RenderResult& r,
                double write) {
    const auto& bvh = scene.bvh().stats();
    double mrays = r.seconds > 0 ? static_cast<double>(r.rays.total()) / r.seconds / 1e6 : 0;
    std::printf("Scene       %s, %s, %s\n", primitiveSummary(scene.primitives).c_str(),
                count(scene.lights.size(), "light", "lights").c_str(),
                count(scene.materials.size(), "material", "materials").c_str());
    if (scene.primitives.instanceCount() > 0)
        std::printf(
            "Instances   %s of %s: %s placed, %s stored once\n",
            count(scene.primitives.instanceCount(), "instance", "instances").c_str(),
            count(scene.primitives.sharedMeshCount(), "shared mesh", "shared meshes").c_str(),
            count(scene.primitives.instancedTriangleCount(), "triangle", "triangles").c_str(),
            count(scene.sharedTriangleCount(), "triangle", "triangles").c_str());
    std::printf("BVH         %u nodes, %u leaves, depth %u, %.2f MB", bvh.nodes, bvh.leaves,
                bvh.maxDepth, static_cast<double>(bvh.bytes) / 1e6);
    if (scene.primitives.sharedMeshCount() > 0)
        std::printf(" + shared meshes %.2f MB", static_cast<double>(scene.sharedBvhBytes()) / 1e6);
    std::printf("\n");
    std::printf("Time        parse %.3f s, build %.3f s%s, render %.3f s, write %.3f s\n", parse,
                build, bvh.refitted ? " (refit)" : "", r.seconds, write);
    std::printf("Rays        %llu camera, %llu shadow, %llu reflection, %llu total\n",
                static_cast<unsigned long long>(r.rays.camera),
                static_cast<unsigned long long>(r.rays.shadow),
                static_cast<unsigned long long>(r.rays.reflection),
                static_cast<unsigned long long>(r.rays.total()));
    std::printf("Throughput  %.2f Mrays/s\n", mrays);
    // Non-zero only through a bug: NaN or infinite radiance, repaired before the film.
    std::printf("Repaired    %llu non-finite radiance values\n",
                static_cast<unsigned long long>(r.rays.nonFinite));
}

std::optional<double> Options::seconds() const {
    if (timeAt) return timeAt;
    if (frame) return static_cast<double>(*frame) / fps;
    if (!animation.empty()) return 0.0;
    return std::nullopt;
}

std::string parseFrameRange(const std::string& text, FrameRange& out) {
    const std::string form =
        "expected A:B or A:B:STEP (frames A to B, every STEP-th), got '" + text + "'";
    long long v[3] = {0, 0, 1};
    size_t at = 0, fields = 0;
    for (bool whole = false; !whole; ++fields) {
        if (fields == 3) return form;
        const size_t end = std::min(text.find(':', at), text.size());
        auto [p, ec] = std::from_chars(text.data() + at, text.data() + end, v[fields]);
        if (at == end || ec != std::errc() || p != text.data() + end) return form;
        whole = end == text.size();
        at = end + 1;
    }
    if (fields < 2) return form;
    if (std::abs(v[0]) > kMaxFrame || std::abs(v[1]) > kMaxFrame)
        return "frames must be -" + std::to_string(kMaxFrame) + " to " + std::to_string(kMaxFrame) +
               ", got '" + text + "'";
    if (v[1] < v[0]) return "the last frame comes before the first in '" + text + "'";
    if (v[2] < 1) return "the step must be at least 1 in '" + text + "'";
    out = {v[0], v[1], v[2]};
    return {};
}

std::string parseShutter(const std::string& text, double& open, double& close) {
    const std::string form =
        "expected OPEN:CLOSE in frames from the frame rendered (-0.25:0.25 is Cycles' shutter "
        "0.5 centred on it), got '" +
        text + "'";
    const size_t colon = text.find(':');
    if (colon == std::string::npos) return form;
    double v[2];
    const char* ends[2] = {text.data() + colon, text.data() + text.size()};
    const char* at = text.data();
    for (int i = 0; i < 2; ++i) {
        auto [p, ec] = std::from_chars(at, ends[i], v[i]);
        if (at == ends[i] || ec != std::errc() || p != ends[i] || !std::isfinite(v[i])) return form;
        at = ends[i] + 1;
    }
    if (std::abs(v[0]) > 1000 || std::abs(v[1]) > 1000)
        return "the shutter must lie within 1000 frames of the frame, got '" + text + "'";
    if (v[1] < v[0]) return "the shutter closes before it opens in '" + text + "'";
    open = v[0];
    close = v[1];
    return {};
}

std::string parseBounces(const std::string& text, BounceOptions& out) {
    const std::string kinds = "total, diffuse, glossy, transmission or volume";
    auto number = [&](std::string_view v, int& n) -> std::string {
        auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
        if (v.empty() || ec != std::errc() || p != v.data() + v.size() || n < 1 ||
            n > kMaxDepthLimit)
            return "each limit must be 1 to " + std::to_string(kMaxDepthLimit) + ", got '" +
                   std::string(v) + "'";
        return {};
    };
    if (!text.empty() && std::isdigit(static_cast<unsigned char>(text[0])))
        return number(text, out.total);
    BounceOptions read;
    for (size_t at = 0; at <= text.size();) {
        const size_t end = std::min(text.find(',', at), text.size());
        const std::string_view item(text.data() + at, end - at);
        const size_t eq = item.find('=');
        if (eq == std::string_view::npos)
            return "expected N or KIND=N,... (KIND " + kinds + "), got '" + text + "'";
        const std::string_view kind = item.substr(0, eq);
        int* slot = kind == "total"          ? &read.total
                    : kind == "diffuse"      ? &read.diffuse
                    : kind == "glossy"       ? &read.glossy
                    : kind == "transmission" ? &read.transmission
                    : kind == "volume"       ? &read.volume
                                             : nullptr;
        if (!slot) return "unknown kind '" + std::string(kind) + "': expected " + kinds;
        if (std::string problem = number(item.substr(eq + 1), *slot); !problem.empty())
            return problem;
        at = end + 1;
    }
    out = read;
    return {};
}

std::string frameFileName(const std::string& pattern, long long frame) {
    for (size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] == '#') {  // Blender's: a run of #s is the number, zero-padded
            size_t end = pattern.find_first_not_of('#', i);
            if (end == std::string::npos) end = pattern.size();
            char buf[32];
            std::snprintf(buf, sizeof buf, "%0*lld", static_cast<int>(end - i), frame);
            return pattern.substr(0, i) + buf + pattern.substr(end);
        }
        if (pattern[i] != '%') continue;
        size_t j = i + 1;
        bool zero = j < pattern.size() && pattern[j] == '0';
        if (zero) ++j;
        int width = 0;
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) &&
               width < 100)
            width = width * 10 + (pattern[j++] - '0');
        if (j < pattern.size() && pattern[j] == 'd') {
            char buf[128];
            std::snprintf(buf, sizeof buf, zero ? "%0*lld" : "%*lld", width, frame);
            return pattern.substr(0, i) + buf + pattern.substr(j + 1);
        }
    }
    return {};
}

std::string sequencePattern(const Options& opt, std::string& pattern) {
    pattern = opt.output;
    if (pattern.empty())
        pattern = std::filesystem::path(opt.scene.empty() ? "glint" : opt.scene).stem().string() +
                  "_%04d.png";
    if (!frameFileName(pattern, 0).empty()) return {};
    return "--frames " + opt.frames +
           " writes a file per frame: -o needs a frame number in its name, as out_%04d.png or "
           "out_####.png, got '" +
           pattern + "'";
}

DisplayTransform displayFor(const Options& opt, const Scene& scene) {
    DisplayTransform display{std::isnan(opt.exposure) ? scene.display.exposure : opt.exposure,
                             scene.display.srgb, scene.display.toneMap};
    if (opt.srgb != 0) display.srgb = opt.srgb > 0;
    if (!opt.toneMap.empty()) display.toneMap = *toneMapNamed(opt.toneMap);
    return display;
}

void applyRenderSettings(const Options& opt, Scene& scene) {
    if (opt.maxDepth >= 0) scene.maxDepth = opt.maxDepth;
    BounceOptions b;
    if (!opt.maxBounces.empty() && parseBounces(opt.maxBounces, b).empty()) {
        if (b.total > 0) scene.maxDepth = b.total;
        for (auto [given, limit] : {std::pair{b.diffuse, &scene.bounces.diffuse},
                                    {b.glossy, &scene.bounces.glossy},
                                    {b.transmission, &scene.bounces.transmission},
                                    {b.volume, &scene.bounces.volume}})
            if (given > 0) *limit = given;
    }
    scene.clampIndirect = opt.clampIndirect;
    scene.caustics = opt.caustics == "on";
    if (!opt.integrator.empty()) scene.integrator = opt.integrator;
}

void prepareScene(const Options& opt, Prepared& out, std::vector<Diagnostic>& warnings,
                  AssetCache* assets, const SceneText* source) {
    using Clock = std::chrono::steady_clock;
    const bool demo = opt.scene.empty() && !source;
    const std::string name = demo ? "demo.test" : source ? source->name : opt.scene;
    auto optionWarning = [&](std::string message) {
        out.optionWarnings.push_back(std::move(message));
    };
    int width = 0, height = 0;
    if (!opt.size.empty()) {
        if (std::string problem = parseSize(opt.size, width, height); !problem.empty())
            throw UsageError(problem);
    }
    if (std::string problem = denoiserProblem(opt.denoiser, opt.denoiseQuality); !problem.empty())
        throw UsageError(problem);
    Isa kernels = Bvh::named(opt.kernels);
    if (kernels == Isa::Avx2 && Bvh::bestIsa() != Isa::Avx2)
        throw UsageError(
            "--kernels avx2: this CPU (or this build of glint) has no AVX2; use "
            "auto or portable");
    if ((demo || source) && !opt.camera.empty())
        throw UsageError("--camera chooses a model file's camera: name a model or scene to render");
    if (!opt.output.empty() && !imageFormatFor(opt.output))
        throw UsageError("cannot write '" + opt.output + "': unknown image format (use " +
                         kImageExtensions + ")");
    // A model's look: the studio with the path tracer, the classic one with Whitted's.
    ModelLook look;
    look.studio = opt.integrator != "whitted";
    if (!opt.ground.empty()) {
        look.ground = opt.ground == "shadow"  ? ModelGround::Shadow
                      : opt.ground == "floor" ? ModelGround::Floor
                                              : ModelGround::None;
        if (!look.studio && look.ground == ModelGround::Shadow)
            throw UsageError(
                "--ground shadow needs the path tracer; with --integrator whitted use --ground "
                "floor or none");
    }
    std::optional<std::shared_ptr<const EnvironmentMap>> environment;
    if (!opt.environment.empty()) {
        try {
            environment = environmentNamed(opt.environment);
        } catch (const RenderError& e) {
            throw RenderError(std::string("--environment: ") + e.what());
        }
        look.environment = environment;
    }

    // Parse.
    auto t0 = Clock::now();
    std::unique_ptr<Scene> scene;
    bool framed = false;  // a model framed as a scene
    if (demo) {
        scene = parseCourseScene(kDemoScene, "demo.test", warnings);
    } else if (source) {
        CourseOptions course;
        course.lenient = opt.lenient;
        course.assets = assets;
        course.models = source->models;
        scene = parseCourseScene(source->text, source->name, warnings, course);
    } else {
        LoadOptions options;
        options.width = width;
        options.height = height;
        options.lenient = opt.lenient;
        options.camera = CameraChoice::parse(opt.camera);
        options.variant = opt.variant;
        options.look = look;
        if (std::optional<double> t = opt.seconds()) {
            options.time.animation = opt.animation;
            options.time.seconds = *t;
        }
        if (!opt.shutter.empty()) {
            double open = 0, close = 0;
            parseShutter(opt.shutter, open, close);  // checked with the options
            if (close > open) {
                options.time.animation = opt.animation;
                options.time.seconds = opt.seconds().value_or(0);
                options.time.shutterOpen = open / opt.fps;
                options.time.shutterClose = close / opt.fps;
            }
        }
        options.assets = assets;
        ModelScene m = loadSceneFile(opt.scene, warnings, options);
        scene = std::move(m.scene);
        out.note = std::move(m.note);
        framed = m.framed;
        out.extensions = std::move(m.extensions);
        out.animations = std::move(m.animations);
    }
    double parseSeconds = secondsSince(t0);
    if (width > 0) {
        scene->width = width;
        scene->height = height;
    }
    if (opt.fovy > 0 && scene->camera) scene->camera->fovyDegrees = opt.fovy;
    if (opt.fovy > 0)
        for (CameraSpec& c : scene->cameraMotion) c.fovyDegrees = opt.fovy;
    applyRenderSettings(opt, *scene);
    if (opt.clampIndirect > 0 && scene->integrator != "path")
        optionWarning("--clamp-indirect applies to the path tracer; integrator '" +
                      scene->integrator + "' ignores it");
    if (!framed) {  // a model's environment and ground were chosen when it was framed
        if (environment) scene->environment = *environment;
        if (!opt.ground.empty())
            optionWarning("--ground applies to models (.obj, .gltf, .glb) only; '" + name +
                          "' is a scene: ignored");
    }
    // How the image is shown: the scene's way (PBR Neutral and sRGB for a model), or the
    // command line's.
    const DisplayTransform display = displayFor(opt, *scene);

    // Where the image goes: -o, else the scene's output line, else <scene-stem>.png.
    std::string output = opt.output;
    if (output.empty()) output = scene->output;
    if (output.empty()) output = std::filesystem::path(name).stem().string() + ".png";
    if (demo && opt.output.empty()) output = "glint.png";

    std::optional<ImageFormat> format = imageFormatFor(output);
    if (!format)
        throw RenderError("cannot write '" + output + "': unknown image format (use " +
                          kImageExtensions + ", or choose a file with -o)");
    // Float files hold linear radiance: the tone mapper and the sRGB curve are for 8-bit files
    // only.
    if (opt.srgb > 0 && isFloatFormat(*format))
        optionWarning("--srgb applies to 8-bit outputs (.png, .ppm) only; '" + output +
                      "' is written linear");
    if (!opt.toneMap.empty() && isFloatFormat(*format))
        optionWarning("--tonemap applies to 8-bit outputs (.png, .ppm) only; '" + output +
                      "' is written linear");
    out.scene = std::move(scene);
    out.display = display;
    out.output = output;
    out.kernels = kernels;
    out.parseSeconds = parseSeconds;
    out.demo = demo;
    out.model = framed;
}

int prepare(const Options& opt, Prepared& out, AssetCache* assets) {
    std::vector<Diagnostic> warnings;
    auto report = [&] {
        for (const auto& w : warnings) std::fprintf(stderr, "%s\n", w.format("warning").c_str());
        if (!out.note.empty() && !opt.quiet && !opt.noteSaid)
            std::fprintf(stderr, "glint: %s\n", out.note.c_str());
        for (const std::string& w : out.optionWarnings)
            std::fprintf(stderr, "glint: warning: %s\n", w.c_str());
    };
    try {
        prepareScene(opt, out, warnings, assets);
    } catch (const UsageError& e) {
        report();
        return usageError(e.what());
    } catch (const SceneError& e) {
        report();
        std::fprintf(stderr, "%s\n", e.what());
        return kExitSceneError;
    } catch (const RenderError& e) {
        report();
        std::fprintf(stderr, "glint: error: %s\n", e.what());
        return kExitSceneError;
    }
    report();
    return kGoOn;
}

}  // namespace glint::cli
