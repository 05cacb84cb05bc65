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
#include "glint/io/course/course_loader.h"
#include "glint/io/image/environment_io.h"
#include "glint/io/image/image_io.h"
#include "glint/io/registry.h"
#include "glint/render/adaptive.h"
#include "glint/render/integrator.h"
#include "glint/render/piece.h"
#include "glint/render/progressive.h"
#include "glint/scene/studio_environment.h"

namespace glint::cli {
namespace {

/// Frames --frame and --frames may name: ten million, 115 hours at 24 fps.
constexpr long long kMaxFrame = 10'000'000;

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
        out.result.film = denoiseFilm(out.result.film, out.result.aovs, pool);
        out.denoiseSeconds = secondsSince(t);
    }
    return out;
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

/// An integer option within [lo, hi], with plain messages for anything else.
CLI::Validator integerIn(long long lo, long long hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            long long v = 0;
            auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            if (ec != std::errc() || p != text.data() + text.size())
                return "expected an integer, got '" + text + "'";
            if (v < lo || v > hi)
                return "must be " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " +
                       text;
            return {};
        },
        "", "");
}

/// A finite real number within [lo, hi], with plain messages for anything else.
CLI::Validator numberIn(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            double v = 0;
            auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            if (ec != std::errc() || p != text.data() + text.size() || !std::isfinite(v))
                return "expected a number, got '" + text + "'";
            auto str = [](double d) {
                char buf[32];
                return std::string(buf, std::to_chars(buf, buf + sizeof buf, d).ptr);
            };
            if (v < lo || v > hi) return "must be " + str(lo) + " to " + str(hi) + ", got " + text;
            return {};
        },
        "", "");
}

DisplayTransform DisplayOptions::over(DisplayTransform base) const {
    if (exposure) base.exposure = *exposure;
    if (srgb != 0) base.srgb = srgb > 0;
    if (!toneMap.empty()) base.toneMap = *toneMapNamed(toneMap);
    return base;
}

void addDisplayOptions(CLI::App& app, DisplayOptions& d, const std::string& unchanged) {
    app.add_option_function<double>(
           "--exposure", [&d](double ev) { d.exposure = ev; },
           "Multiply radiance by 2^EV before writing, -64 to 64 (default: " + unchanged + ")")
        ->check(numberIn(-64, 64))
        ->type_name("EV");
    app.add_flag_callback(
        "--srgb", [&d] { d.srgb = 1; },
        "Encode 8-bit outputs with the sRGB curve (default: " + unchanged + ")");
    app.add_flag_callback(
        "--no-srgb", [&d] { d.srgb = -1; }, "Encode 8-bit outputs with the course's floor(255 c)");
    app.add_option("--tonemap", d.toneMap,
                   "neutral, aces or clamp, for 8-bit outputs (default: " + unchanged + ")")
        ->check(CLI::IsMember({"neutral", "aces", "clamp"}))
        ->type_name("NAME");
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
    DisplayTransform display{opt.exposure, scene.display.srgb, scene.display.toneMap};
    if (opt.srgb != 0) display.srgb = opt.srgb > 0;
    if (!opt.toneMap.empty()) display.toneMap = *toneMapNamed(opt.toneMap);
    return display;
}

void applyRenderSettings(const Options& opt, Scene& scene) {
    if (opt.maxDepth >= 0) scene.maxDepth = opt.maxDepth;
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
        if (!out.note.empty() && !opt.quiet) std::fprintf(stderr, "glint: %s\n", out.note.c_str());
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

void addOptions(CLI::App& app, Options& opt) {
    app.add_option("SCENE", opt.scene,
                   "Scene file to render (CSE167x .test format), or an .obj, .gltf, .glb, .ply "
                   "or .stl model to frame");

    const char* input = "Input";
    app.add_flag("--lenient", opt.lenient,
                 "Skip unknown commands and ignore unmatched popTransforms in scene files, with "
                 "a warning, as the course's own parser did (default: they are errors)")
        ->group(input);
    app.add_option("--camera", opt.camera,
                   "Which camera to render a model file through: its number N (from 0, in the "
                   "order of the file's node tree), the name of the camera or of its node, none "
                   "to ignore the file's cameras and frame the model, or "
                   "orbit:THETA,PHI,RADIUS[,TX,TY,TZ] for a camera on a sphere around a target "
                   "(degrees; the Khronos Render Fidelity and model-viewer orbit, 45 degrees "
                   "vertical field of view; also for scene files) (default: its first "
                   "perspective camera)")
        ->group(input)
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                if (text.empty()) return "expected a camera number, a name, none or orbit:...";
                try {
                    CameraChoice::parse(text);
                } catch (const std::invalid_argument& e) {
                    return e.what();
                }
                return {};
            },
            "", ""))
        ->type_name("N|NAME|none|orbit:...");
    app.add_option("--fov", opt.fovy,
                   "Vertical field of view in degrees, overriding the camera's, 0.01 to 179")
        ->group(input)
        ->check(numberIn(0.01, 179))
        ->type_name("DEG");

    const char* time = "Time (docs/animation.md)";
    app.add_option("--animation", opt.animation,
                   "Which of a model's animations to play: its number (from 0) or name "
                   "(default: the first); also for the glTF files a scene's mesh lines name")
        ->group(time)
        ->type_name("N|NAME");
    auto* frameOption = app.add_option_function<long long>(
                               "--frame", [&opt](long long f) { opt.frame = f; },
                               "Render frame N: the animation at N / --fps seconds (frame 0 is "
                               "its time 0)")
                            ->group(time)
                            ->check(integerIn(-kMaxFrame, kMaxFrame))
                            ->type_name("N");
    auto* timeOption = app.add_option_function<double>(
                              "--time-at", [&opt](double t) { opt.timeAt = t; },
                              "Render the animation at SECONDS (the file's own time), -1e6 to 1e6")
                           ->group(time)
                           ->check(numberIn(-1e6, 1e6))
                           ->type_name("SECONDS");
    auto* framesOption =
        app.add_option("--frames", opt.frames,
                       "Render frames A to B (every STEP-th) into files named by -o's pattern "
                       "(out_%04d.png or out_####.png), loading the file once")
            ->group(time)
            ->check(CLI::Validator(
                [](std::string& text) -> std::string {
                    FrameRange r;
                    return parseFrameRange(text, r);
                },
                "", ""))
            ->type_name("A:B[:STEP]");
    frameOption->excludes(timeOption)->excludes(framesOption);
    timeOption->excludes(framesOption);
    app.add_option("--shutter", opt.shutter,
                   "Motion blur: the shutter is open from OPEN to CLOSE frames from the frame "
                   "rendered (-0.25:0.25 is Cycles' shutter 0.5 centred on it; 0:1 blurs to the "
                   "next frame)")
        ->group(time)
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                double a = 0, b = 0;
                return parseShutter(text, a, b);
            },
            "", ""))
        ->type_name("OPEN:CLOSE");
    app.add_option("--fps", opt.fps, "Frames per second of --frame and --frames, 0.001 to 1000")
        ->group(time)
        ->check(numberIn(0.001, 1000))
        ->type_name("FPS");

    const char* out = "Output";
    app.add_option("-o,--output", opt.output,
                   "Image file to write; .png, .ppm, .pfm or .exr (float). Default: the "
                   "scene's 'output' line, else <scene-stem>.png")
        ->group(out)
        ->type_name("FILE");
    app.add_option("--exposure", opt.exposure,
                   "Multiply radiance by 2^EV before writing, -64 to 64, every format "
                   "(default 0: unchanged)")
        ->group(out)
        ->check(numberIn(-64, 64))
        ->type_name("EV");
    app.add_flag_callback(
           "--srgb", [&opt] { opt.srgb = 1; },
           "Encode 8-bit outputs (.png, .ppm) with the sRGB curve, rounded (default for models; "
           "scenes: the course's clamp and floor(255 c)); float outputs stay linear")
        ->group(out);
    app.add_flag_callback(
           "--no-srgb", [&opt] { opt.srgb = -1; },
           "Encode 8-bit outputs with the course's floor(255 c), also for models")
        ->group(out);
    app.add_option("--tonemap", opt.toneMap,
                   "How radiance is brought into [0, 1] for 8-bit outputs: neutral (Khronos PBR "
                   "Neutral), aces (three.js's ACES filmic, as Khronos' Render Fidelity images), "
                   "clamp (the course's); default: neutral for models, clamp for scenes")
        ->group(out)
        ->check(CLI::IsMember({"neutral", "aces", "clamp"}))
        ->type_name("NAME");

    const char* render = "Rendering";
    app.add_option("-t,--threads", opt.threads,
                   "Threads for the BVH build and the render, 1 to 4096 (default: all hardware "
                   "threads); 1 runs everything on one thread")
        ->group(render)
        ->check(integerIn(1, 4096))
        ->type_name("N");
    app.add_option("--kernels", opt.kernels,
                   std::string("Traversal kernels: auto (the best this CPU runs: ") + Bvh::isa() +
                       " here), avx2, portable (plain C++); every choice gives the same image")
        ->group(render)
        ->check(CLI::IsMember({"auto", "avx2", "portable"}))
        ->type_name("NAME");
    app.add_option("--size", opt.size, "Image size, overriding the scene's 'size'")
        ->group(render)
        ->type_name("WxH");
    app.add_option("--maxdepth", opt.maxDepth,
                   "Maximum reflection depth, 0 to 64, overriding the scene's (models: 8)")
        ->group(render)
        ->check(integerIn(0, kMaxDepthLimit))
        ->type_name("N");
    app.add_option("--clamp-indirect", opt.clampIndirect,
                   "Path tracer: scale each sample's light after two or more bounces down to at "
                   "most X in its largest channel (Cycles' Clamp Indirect): fewer fireflies, "
                   "darker caustics and glossy interreflections (biased); default off")
        ->group(render)
        ->check(numberIn(0, 1e30))
        ->type_name("X");

    app.add_option("--caustics", opt.caustics,
                   "Path tracer: trace the light that glass and mirrors focus onto what the "
                   "camera sees from the lights (a light pass beside the camera's paths; "
                   "unbiased either way); default on")
        ->group(render)
        ->check(CLI::IsMember({"on", "off"}))
        ->type_name("on|off");

    app.add_option(
           "--integrator", opt.integrator,
           "How light is computed, overriding the scene's 'integrator': " + integratorNameList() +
               " (default: whitted, the course's; path for models, whitted giving "
               "them the classic look)")
        ->group(render)
        ->check(CLI::Validator(
            [](std::string& name) -> std::string {
                if (findIntegrator(name)) return {};
                return "unknown integrator '" + name + "' (Glint has " + integratorNameList() + ")";
            },
            "", ""))
        ->type_name("NAME");
    app.add_option("--spp", opt.spp,
                   "Camera rays per pixel, 1 to 65536: stratified, jittered, filtered "
                   "(default: the scene's spp, else 1, the pixel centre; 64 for models); with "
                   "--time, the most")
        ->group(render)
        ->check(integerIn(1, 65536))
        ->type_name("N");
    app.add_option("--time", opt.timeBudget,
                   "Render in passes until SECONDS are spent, 0.01 to 1e6, then average them "
                   "(default: a fixed --spp)")
        ->group(render)
        ->check(numberIn(0.01, 1e6))
        ->type_name("SECONDS");
    app.add_option("--environment", opt.environment,
                   "Surroundings and light: an .hdr or .exr map, 'studio' (Glint's), or 'none' "
                   "(default: the scene's; studio for models)")
        ->group(render)
        ->type_name("FILE");
    app.add_option("--ground", opt.ground,
                   "What a model stands on: shadow (a shadow catcher), floor (grey matte), none "
                   "(default: shadow; floor with --integrator whitted)")
        ->group(render)
        ->check(CLI::IsMember({"shadow", "floor", "none"}))
        ->type_name("NAME");
    app.add_option("--seed", opt.seed,
                   "Seed of every random choice: sub-pixel jitter, lens, area lights, "
                   "glossy rays (default 0)")
        ->group(render)
        ->type_name("N");

    const char* clean = "Clean images (docs/denoising.md)";
    app.add_option("--aov", opt.aov,
                   "Render passes to write as layers of the .exr output: albedo, normal, depth, "
                   "variance, comma-separated, or all")
        ->group(clean)
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                AovSelection sel;
                return parseAovList(text, sel);
            },
            "", ""))
        ->type_name("LIST");
    app.add_flag_callback(
           "--denoise", [&opt] { opt.denoise = 1; },
           "Denoise the image with Glint's feature-guided denoiser (default for models)")
        ->group(clean);
    app.add_flag_callback(
           "--no-denoise", [&opt] { opt.denoise = -1; },
           "Write the image as rendered, with its noise (default for scenes)")
        ->group(clean);
    app.add_option("--noise-threshold", opt.noiseThreshold,
                   "Adaptive sampling: stop sampling a pixel once its relative error is below "
                   "T, 0.0001 to 1 (Cycles' meaning), with --spp as the most and --time as the "
                   "budget (default for models: 0.02, at most 1024 spp and 2.5 s)")
        ->group(clean)
        ->check(numberIn(1e-4, 1))
        ->type_name("T");
    app.add_option("--min-spp", opt.minSpp,
                   "With --noise-threshold: samples every pixel takes first, 2 to 65536 "
                   "(default 16, at most --spp)")
        ->group(clean)
        ->check(integerIn(2, 65536))
        ->type_name("N");

    const char* piece =
        "Frame pieces: any of these writes an OpenEXR piece (-o FILE.exr) for glint merge; they "
        "combine (docs/scale-out.md)";
    auto form = [](std::string (*parse)(std::string_view, int&, int&)) {
        return CLI::Validator(
            [parse](std::string& text) -> std::string {
                int a = 0, b = 0;
                return parse(text, a, b);
            },
            "", "");
    };
    app.add_option("--crop", opt.crop,
                   "Render only pixels x0 to x1-1 across and y0 to y1-1 down, from the top-left "
                   "corner: the upper bounds excluded, as pbrt's --pixelbounds")
        ->group(piece)
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                PixelBounds b;
                return parseCrop(text, b);
            },
            "", ""))
        ->type_name("x0,x1,y0,y1");
    app.add_option("--samples", opt.samples,
                   "Render only samples A to B-1 of each pixel's spp, exactly those the whole "
                   "render takes there (0 <= A < B <= spp)")
        ->group(piece)
        ->check(form(parseSampleRange))
        ->type_name("A:B");
    app.add_option("--part", opt.part,
                   "Render piece K of N (0 <= K < N <= 65536): the rows of 16-pixel tiles whose "
                   "index % N is K, so every piece gets rows from the whole height")
        ->group(piece)
        ->check(form(parsePart))
        ->type_name("K/N");

    const char* info = "Information";
    app.add_flag("--check", opt.check,
                 "Parse and validate the scene, print a summary, render nothing")
        ->group(info);
    app.add_flag("--stats", opt.stats, "Print times per phase, rays traced and Mrays/s")
        ->group(info);
    app.add_flag("-q,--quiet", opt.quiet, "No progress or messages; warnings and errors only")
        ->group(info);
    app.set_version_flag("--version", std::string("glint ") + GLINT_VERSION +
                                          " (traversal kernels: " + Bvh::isa() + ")")
        ->group(info);
    app.set_help_flag("-h,--help", "Print this help and exit")->group(info);
}

}  // namespace glint::cli
