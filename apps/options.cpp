// The command lines of glint, glint merge and glint denoise (options.h): every option, with its
// help text and validator, and the parsing. The only file of glint's that includes CLI11.

#include "options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "glint/accel/bvh.h"
#include "glint/denoise/film_denoise.h"
#include "glint/denoise/unet/blocked.h"
#include "glint/render/film/film.h"
#include "glint/render/film/piece.h"
#include "glint/render/integrators/integrator.h"
#include "glint/scene/model.h"
#include "glint/scene/scene.h"

namespace glint::cli {
namespace {

/// Edit distance between a and b counting a swap of two neighbouring letters as one edit
/// (optimal string alignment): "srbg" is one from "srgb".
size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

/// What `program`'s command line `args` (without the program's name) got wrong, in Glint's
/// words, for the errors CLI11 words its own way: an unknown option (with the nearest known one,
/// as the scene parser suggests commands), one positional too many, an option without its value.
/// Empty for every other error: CLI11's message (and Glint's validators') says it well.
std::string explainUsageError(const CLI::App& app, const CLI::ParseError& e,
                              const std::vector<std::string>& args) {
    // The options by every name they answer to, and whether each takes a value.
    struct Known {
        const CLI::Option* option;
        bool takesValue;
    };
    std::vector<std::pair<std::string, Known>> names;
    std::vector<const CLI::Option*> positionals;
    for (const CLI::Option* o : app.get_options()) {
        const bool takesValue = o->get_items_expected_min() > 0;
        for (const std::string& n : o->get_lnames()) names.push_back({"--" + n, {o, takesValue}});
        for (const std::string& n : o->get_snames()) names.push_back({"-" + n, {o, takesValue}});
        if (!o->nonpositional()) positionals.push_back(o);
    }
    auto find = [&](std::string_view name) -> const Known* {
        for (const auto& [n, k] : names)
            if (n == name) return &k;
        return nullptr;
    };
    auto isNumber = [](const std::string& t) {
        double v;
        auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        return ec == std::errc() && p == t.data() + t.size();
    };
    // Walk the arguments as the parser does: unknown options, and the positionals.
    std::vector<std::string> unknown, given;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& t = args[i];
        if (t == "--") {
            given.insert(given.end(), args.begin() + static_cast<long>(i) + 1, args.end());
            break;
        }
        if (t.size() > 1 && t[0] == '-' && !isNumber(t)) {
            const bool twoDashes = t.rfind("--", 0) == 0;
            const std::string name = twoDashes ? t.substr(0, t.find('=')) : t.substr(0, 2);
            const Known* k = find(name);
            if (!k || (!twoDashes && t.size() > 2 && !k->takesValue)) {
                unknown.push_back(twoDashes ? name : t);
                continue;
            }
            const bool attached = twoDashes ? t.find('=') != std::string::npos : t.size() > 2;
            if (k->takesValue && !attached) ++i;
            continue;
        }
        given.push_back(t);
    }
    if (!unknown.empty()) {
        std::string out;
        for (const std::string& u : unknown) {
            const std::string bare = u.substr(u.find_first_not_of('-'));
            std::string best;
            size_t bestDistance = std::string::npos;
            for (const auto& [n, k] : names) {
                const size_t d = editDistance(bare, n.substr(n.find_first_not_of('-')));
                if (d < bestDistance) bestDistance = d, best = n;
            }
            out += (out.empty() ? "" : "; ") + std::string("unknown option '") + u + "'";
            if (bestDistance == 0)
                out += ": did you mean '" + best + "'? (" +
                       (best.rfind("--", 0) == 0 ? "long options take two dashes)"
                                                 : "short options take one dash)");
            else if (bare.size() > 2 && bestDistance <= std::max<size_t>(1, bare.size() / 3))
                out += ": did you mean '" + best + "'?";
        }
        return out;
    }
    if (dynamic_cast<const CLI::ExtrasError*>(&e) && !positionals.empty() &&
        given.size() > static_cast<size_t>(std::max(1, positionals[0]->get_expected_max()))) {
        std::string list;
        for (size_t i = 0; i < given.size(); ++i)
            list += (i ? (i + 1 == given.size() ? " and '" : ", '") : "'") + given[i] + "'";
        return "one " + positionals[0]->get_name() + " only, got " + list;
    }
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) {
        // CLI11's "--spp: 1 required N missing": the option without its value.
        const std::string what = e.what();
        const std::string name = what.substr(0, what.find(':'));
        if (const Known* k = find(name))
            return "option " + name + " needs a value: " + k->option->get_type_name();
    }
    return {};
}

/// Parses `args` with `app`; on a usage error prints it as `program: error: ...` and returns
/// kExitUsage, after --help or --version 0, else kGoOn.
int parseOrExplain(CLI::App& app, int argc, char** argv, const std::string& program) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        const std::vector<std::string> args(argv + 1, argv + argc);
        const std::string why = explainUsageError(app, e, args);
        if (why.empty()) return app.exit(e) == 0 ? 0 : kExitUsage;
        std::fprintf(stderr, "%s: error: %s\nRun '%s --help' for usage.\n", program.c_str(),
                     why.c_str(), program.c_str());
        return kExitUsage;
    }
    return kGoOn;
}

/// A validator from `problem(text)`: what is wrong with an option's text, empty if nothing.
template <class Problem>
CLI::Validator checkedBy(Problem problem) {
    return CLI::Validator([problem](std::string& text) -> std::string { return problem(text); }, "",
                          "");
}

/// A validator from a parser `parse(text, Out&...)` that returns what is wrong with the text;
/// the values it reads are dropped (the option's callback or variable takes the text).
template <class... Out, class Parse>
CLI::Validator parsedBy(Parse parse) {
    return checkedBy([parse](const std::string& text) {
        std::tuple<Out...> values{};
        return std::apply([&](Out&... out) { return std::string(parse(text, out...)); }, values);
    });
}

/// An integer option within [lo, hi], with plain messages for anything else.
CLI::Validator integerIn(long long lo, long long hi) {
    return checkedBy([lo, hi](const std::string& text) -> std::string {
        long long v = 0;
        auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || p != text.data() + text.size())
            return "expected an integer, got '" + text + "'";
        if (v < lo || v > hi)
            return "must be " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + text;
        return {};
    });
}

/// A finite real number within [lo, hi], with plain messages for anything else.
CLI::Validator numberIn(double lo, double hi) {
    return checkedBy([lo, hi](const std::string& text) -> std::string {
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
    });
}

/// Registers --exposure, --srgb, --no-srgb and --tonemap on `app`; `unchanged` says what an
/// option not given leaves ("the pieces'").
/// What --version says of the denoiser: the network's kernels and weights, or that it has none.
std::string denoiserSummary() {
    if (resolveDenoiser(DenoiserKind::Auto) == DenoiserKind::Nlm)
        return "nlm (no network weights: denoise-weights/README.md)";
    return "oidn, OIDN 2.3's weights, " + std::string(unet::kernelIsaName(unet::bestKernelIsa())) +
           " kernels";
}

/// --denoiser and --denoise-quality (glint and glint denoise).
void addDenoiserOptions(CLI::App& app, std::string& denoiser, std::string& quality,
                        const std::string& group) {
    app.add_option("--denoiser", denoiser,
                   "The denoiser: oidn, Open Image Denoise's network (its published weights, run "
                   "by Glint); nlm, Glint's non-local-means filter; auto, oidn where this build "
                   "has its weights (default)")
        ->group(group)
        ->check(CLI::IsMember({"auto", "oidn", "nlm"}))
        ->type_name("NAME");
    app.add_option("--denoise-quality", quality,
                   "The network's quality: fast, balanced (default) or high (cleans the albedo "
                   "and normal passes first with networks of their own: about 6x balanced's time)")
        ->group(group)
        ->check(CLI::IsMember({"fast", "balanced", "high"}))
        ->type_name("NAME");
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

}  // namespace

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
        ->check(checkedBy([](const std::string& text) -> std::string {
            if (text.empty()) return "expected a camera number, a name, none or orbit:...";
            try {
                CameraChoice::parse(text);
            } catch (const std::invalid_argument& e) {
                return e.what();
            }
            return {};
        }))
        ->type_name("N|NAME|none|orbit:...");
    app.add_option("--variant", opt.variant,
                   "A glTF model's material variant (KHR_materials_variants), by name or number "
                   "from 0; --check lists them (default: the file's own materials)")
        ->group(input)
        ->type_name("NAME|N");
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
            ->check(parsedBy<FrameRange>(parseFrameRange))
            ->type_name("A:B[:STEP]");
    frameOption->excludes(timeOption)->excludes(framesOption);
    timeOption->excludes(framesOption);
    app.add_option("--shutter", opt.shutter,
                   "Motion blur: the shutter is open from OPEN to CLOSE frames from the frame "
                   "rendered (-0.25:0.25 is Cycles' shutter 0.5 centred on it; 0:1 blurs to the "
                   "next frame)")
        ->group(time)
        ->check(parsedBy<double, double>(parseShutter))
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
                   "(default 0: unchanged; for a model lit by its own lights in physical units, "
                   "the exposure Glint chooses and says)")
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
                   "Maximum reflection depth, 0 to 64, overriding the scene's (models: 12)")
        ->group(render)
        ->check(integerIn(0, kMaxDepthLimit))
        ->type_name("N");
    app.add_option("--max-bounces", opt.maxBounces,
                   "Path tracer's bounce limits as Cycles' Light Paths: in all (N, as "
                   "--maxdepth) or by kind (total=12,diffuse=4,glossy=4,transmission=12,"
                   "volume=4, any of them), each 1 to 64, 1 being direct light only (Cycles' "
                   "0); models: total=12,transmission=12,diffuse=8,glossy=8,volume=8")
        ->group(render)
        ->check(parsedBy<BounceOptions>(parseBounces))
        ->type_name("LIST");
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
        ->check(checkedBy([](const std::string& name) -> std::string {
            if (findIntegrator(name)) return {};
            return "unknown integrator '" + name + "' (Glint has " + integratorNameList() + ")";
        }))
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

    const char* clean = "Clean images (docs/clean-images.md)";
    app.add_option("--aov", opt.aov,
                   "Render passes to write as layers of the .exr output: albedo, normal, depth, "
                   "variance, comma-separated, or all")
        ->group(clean)
        ->check(parsedBy<AovSelection>(parseAovList))
        ->type_name("LIST");
    app.add_flag_callback(
           "--denoise", [&opt] { opt.denoise = 1; },
           "Denoise the image (default for models; --denoiser says with what)")
        ->group(clean);
    app.add_flag_callback(
           "--no-denoise", [&opt] { opt.denoise = -1; },
           "Write the image as rendered, with its noise (default for scenes)")
        ->group(clean);
    addDenoiserOptions(app, opt.denoiser, opt.denoiseQuality, clean);
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
    app.add_option("--crop", opt.crop,
                   "Render only pixels x0 to x1-1 across and y0 to y1-1 down, from the top-left "
                   "corner: the upper bounds excluded, as pbrt's --pixelbounds")
        ->group(piece)
        ->check(parsedBy<PixelBounds>(parseCrop))
        ->type_name("x0,x1,y0,y1");
    app.add_option("--samples", opt.samples,
                   "Render only samples A to B-1 of each pixel's spp, exactly those the whole "
                   "render takes there (0 <= A < B <= spp)")
        ->group(piece)
        ->check(parsedBy<int, int>(parseSampleRange))
        ->type_name("A:B");
    app.add_option("--part", opt.part,
                   "Render piece K of N (0 <= K < N <= 65536): the rows of 16-pixel tiles whose "
                   "index % N is K, so every piece gets rows from the whole height")
        ->group(piece)
        ->check(parsedBy<int, int>(parsePart))
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
                                          " (traversal kernels: " + Bvh::isa() +
                                          "; denoiser: " + denoiserSummary() + ")")
        ->group(info);
    app.set_help_flag("-h,--help", "Print this help and exit")->group(info);
}

int parseOptions(int argc, char** argv, Options& opt) {
    CLI::App app{
        "Glint renders scenes in the CSE167x ray tracer format (and Glint's extensions)."
        "\nWithout SCENE it renders a built-in demo scene to glint.png; given a model (.obj,"
        "\n.gltf, .glb, .ply, .stl) it shows it as a glTF viewer does: path traced in a studio"
        "\nenvironment, on a ground shadow, through the Khronos PBR Neutral tone mapper.",
        "glint"};
    app.get_formatter()->column_width(30);
    // One style for every usage error, whether CLI11 or Glint finds it.
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("glint: error: ") + e.what() + "\nRun 'glint --help' for usage.\n";
    });
    app.footer(
        "Frame pieces rendered with --part, --crop or --samples are merged with\n"
        "  glint merge -o OUT PIECE.exr...   (glint merge --help; docs/scale-out.md)\n"
        "A render saved as OpenEXR (with its passes: --aov all) is denoised with\n"
        "  glint denoise IN.exr -o OUT       (glint denoise --help; docs/clean-images.md)");
    addOptions(app, opt);

    const int code = parseOrExplain(app, argc, argv, "glint");
    for (int i = 2; i < argc && code == kExitUsage; ++i)
        if (std::string_view(argv[i]) == "merge" || std::string_view(argv[i]) == "denoise") {
            std::fprintf(stderr, "(the command comes first: glint %s ...; glint %s --help)\n",
                         argv[i], argv[i]);
            break;
        }
    return code;
}

int parseMergeOptions(int argc, char** argv, MergeOptions& opt) {
    CLI::App app{
        "Merges frame pieces that glint rendered with --part, --crop or --samples into one "
        "image,\nexactly the image a single glint run writes (docs/scale-out.md). Checks that "
        "the pieces\nare of one frame (scene, size, samples, seed, settings, version) and cover "
        "each pixel's\nsamples exactly once; they are added in a fixed order whatever the order "
        "named.",
        "glint merge"};
    app.get_formatter()->column_width(30);
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("glint merge: error: ") + e.what() +
               "\nRun 'glint merge --help' for usage.\n";
    });
    app.add_option("PIECE", opt.pieces, "Piece files (.exr) that glint wrote")
        ->required()
        ->type_name("FILE");
    app.add_option("-o,--output", opt.output, "Image file to write; .png, .ppm, .pfm or .exr")
        ->required()
        ->type_name("FILE");
    addDisplayOptions(app, opt.shown, "as the pieces were rendered");
    app.add_flag("-q,--quiet", opt.quiet, "No messages; warnings and errors only");
    app.set_help_flag("-h,--help", "Print this help and exit");
    return parseOrExplain(app, argc, argv, "glint merge");
}

int parseDenoiseOptions(int argc, char** argv, DenoiseOptions& opt) {
    CLI::App app{
        "Denoises a render saved as OpenEXR, guided by the render passes the file holds "
        "(albedo,\nnormal, depth, variance: glint --aov all, or glint merge of such pieces). "
        "Without passes it\nestimates the noise from the image alone, which blurs texture.",
        "glint denoise"};
    app.get_formatter()->column_width(30);
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("glint denoise: error: ") + e.what() +
               "\nRun 'glint denoise --help' for usage.\n";
    });
    app.add_option("INPUT", opt.input, "The render (.exr), with its passes as layers")
        ->required()
        ->type_name("FILE");
    app.add_option("-o,--output", opt.output,
                   "Image file to write; .png, .ppm, .pfm or .exr (an .exr keeps the passes)")
        ->required()
        ->type_name("FILE");
    app.add_option("-t,--threads", opt.threads,
                   "Threads, 1 to 4096 (default: all hardware threads)")
        ->check(integerIn(1, 4096))
        ->type_name("N");
    addDenoiserOptions(app, opt.denoiser, opt.quality, "Options");
    addDisplayOptions(app, opt.shown, "off");
    app.add_flag("-q,--quiet", opt.quiet, "No messages; errors only");
    app.set_help_flag("-h,--help", "Print this help and exit");
    return parseOrExplain(app, argc, argv, "glint denoise");
}

}  // namespace glint::cli
