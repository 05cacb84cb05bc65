#pragma once
// What the glint command line shares with its other entry points (the MPI mode): the options
// (parsed in options.cpp), loading and setting up a scene as they ask, and the reports. Usage
// errors exit 2, scene and render errors exit 1.

#include <chrono>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "glint/accel/bvh.h"
#include "glint/denoise/film_denoise.h"
#include "glint/io/registry.h"
#include "glint/render/film/display.h"
#include "glint/render/renderer.h"
#include "glint/scene/model.h"
#include "glint/scene/scene.h"

namespace glint::cli {

constexpr int kExitSceneError = 1;
constexpr int kExitUsage = 2;
constexpr int kGoOn = -1;  ///< From prepare(): no error, go on.

/// A problem with the options as given (the command line exits 2 for it).
class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// A model's default sampling (docs/clean-images.md): adaptive to this noise threshold, within
/// this many seconds of rendering; and the most samples per pixel of an adaptive render when
/// --spp does not say.
constexpr double kModelNoiseThreshold = 0.02;
constexpr double kModelSeconds = 2.5;
constexpr int kAdaptiveMaxSpp = 1024;

/// Frames --frame and --frames may name: ten million, 115 hours at 24 fps.
constexpr long long kMaxFrame = 10'000'000;

/// The command line, as parsed.
struct Options {
    std::string scene;
    std::string output;
    int threads = 0;  ///< 0: all hardware threads.
    std::string kernels = "auto";
    std::string size;
    int maxDepth = -1;
    std::string maxBounces;       ///< --max-bounces: limits by kind (parseBounces).
    double clampIndirect = 0;     ///< --clamp-indirect; 0: none.
    std::string caustics = "on";  ///< --caustics: the path tracer's light pass, on or off.
    std::string integrator;       ///< Empty: the scene's `integrator`, else whitted.
    int spp = 0;                  ///< 0: the scene's `spp`, else 1.
    uint64_t seed = 0;
    /// EV: radiance times 2^exposure before writing; NaN: not given (the scene's, 0 but for a
    /// model lit in physical units).
    double exposure = std::numeric_limits<double>::quiet_NaN();
    int srgb = 0;             ///< sRGB curve for 8-bit outputs: 1 on, -1 off, 0 the scene's.
    std::string toneMap;      ///< Empty: the scene's (PBR Neutral for models, else clamp).
    std::string environment;  ///< Empty: the scene's; "studio", "none" or a file.
    std::string ground;       ///< Empty: the model's (shadow); "shadow", "floor" or "none".
    double timeBudget = 0;    ///< Seconds; 0: render a fixed number of samples.
    bool check = false;
    bool stats = false;
    bool quiet = false;
    /// A later frame of a --frames sequence: the model's note (its framing, its pose) was
    /// said at the first frame and is not repeated.
    bool noteSaid = false;
    bool lenient = false;
    std::string camera;   ///< --camera: empty for the model's first camera.
    std::string variant;  ///< --variant: a glTF file's material variant; empty: its defaults.
    double fovy = 0;      ///< --fov: the vertical field of view in degrees; 0: the camera's.
    // A piece of the frame for `glint merge` (apps/piece.h); empty: the whole image.
    std::string crop;     ///< --crop x0,x1,y0,y1
    std::string samples;  ///< --samples A:B
    std::string part;     ///< --part K/N
    // Clean images (docs/clean-images.md).
    std::string aov;  ///< --aov: passes to write as layers of the EXR output.
    int denoise = 0;  ///< 1 --denoise, -1 --no-denoise, 0 the default (on for models).
    std::string denoiser = "auto";            ///< --denoiser: auto, oidn or nlm.
    std::string denoiseQuality = "balanced";  ///< --denoise-quality: fast, balanced or high.
    double noiseThreshold = 0;                ///< --noise-threshold; 0: a fixed number of samples.
    int minSpp = 0;                           ///< --min-spp; 0: the default.
    // Time (docs/animation.md).
    std::string animation;           ///< --animation: its index or name; empty for the first.
    std::optional<double> timeAt;    ///< --time-at SECONDS
    std::optional<long long> frame;  ///< --frame N
    double fps = 24;                 ///< --fps
    std::string frames;              ///< --frames A:B[:STEP]: a sequence
    std::string shutter;             ///< --shutter OPEN:CLOSE, in frames from the frame

    /// The time to pose models at: --time-at, or --frame / --fps, or 0 with --animation alone;
    /// none when no animation is asked for.
    std::optional<double> seconds() const;
};

/// Parses --shutter OPEN:CLOSE (frames from the frame rendered, OPEN <= CLOSE, each within
/// +-1000); returns what is wrong, or nothing.
std::string parseShutter(const std::string& text, double& open, double& close);

/// --max-bounces: the path tracer's bounce limits, each -1 where not given.
struct BounceOptions {
    int total = -1, diffuse = -1, glossy = -1, transmission = -1, volume = -1;
};
/// Parses N (bounces in all, as --maxdepth) or KIND=N,... with KIND total, diffuse, glossy,
/// transmission or volume and N from 1 to 64; returns what is wrong, or nothing.
std::string parseBounces(const std::string& text, BounceOptions& out);

/// A range of frames, --frames A:B[:STEP]: A to B inclusive, every STEP-th.
struct FrameRange {
    long long first = 0, last = 0, step = 1;
    long long count() const { return (last - first) / step + 1; }
};
/// Parses A:B[:STEP] (A <= B, STEP >= 1); returns what is wrong, or nothing.
std::string parseFrameRange(const std::string& text, FrameRange& out);
/// The file of frame `frame` in `pattern`: its first %d, %0Nd or run of #s replaced by the
/// number (at least N digits); empty when the pattern has none.
std::string frameFileName(const std::string& pattern, long long frame);
/// The file name pattern of the sequence --frames asks for: -o, else <scene-stem>_%04d.png (or
/// glint_%04d.png for the demo). Returns what is wrong with it (no frame number), or nothing.
std::string sequencePattern(const Options& opt, std::string& pattern);

/// A scene loaded and set up as the options ask, and where and how its image goes.
struct Prepared {
    std::unique_ptr<Scene> scene;
    DisplayTransform display;
    std::string output;  ///< The image file to write.
    Isa kernels = Isa::Auto;
    double parseSeconds = 0;
    bool demo = false;   ///< No scene named: the built-in demo.
    bool model = false;  ///< A model file framed in the studio (not a scene).
    /// A model file's format extensions and what Glint does with each (`--check` lists them).
    std::vector<FormatExtension> extensions;
    /// A model file's animations (`--check` lists them).
    std::vector<ModelAnimation> animations;
    std::string note;  ///< For a bare model: the camera, lights and floor Glint chose.
    /// Options that do not apply to this scene or output, said plainly ("--srgb applies to
    /// 8-bit outputs ...").
    std::vector<std::string> optionWarnings;
};

/// A scene given as the text of a scene file rather than a file (the Python module's Scene
/// builder, docs/python.md), with the models its `mesh` lines name (CourseOptions::models).
struct SceneText {
    std::string text;
    std::string name;  ///< For messages, as a file name.
    std::map<std::string, std::shared_ptr<const Model>> models;
};

/// Loads the scene `opt` names (or `source`, or the demo) and applies the options to it; the
/// BVH is not built yet. The loaders' warnings go to `warnings`. Throws UsageError for options that
/// do not fit, SceneError for a bad scene (with its file position) and RenderError for anything
/// else that cannot be read (glint.load in Python reports each as its own exception). `assets`:
/// where model files are kept between the frames of a sequence (null: nowhere).
void prepareScene(const Options& opt, Prepared& out, std::vector<Diagnostic>& warnings,
                  AssetCache* assets = nullptr, const SceneText* source = nullptr);

/// How the image of `scene` is shown: the scene's way (PBR Neutral and sRGB for a model), with
/// what --exposure, --srgb, --no-srgb and --tonemap change.
DisplayTransform displayFor(const Options& opt, const Scene& scene);

/// Applies what `opt` says of how the scene renders and does not change what it holds: the
/// integrator, --max-depth, --clamp-indirect and --caustics.
void applyRenderSettings(const Options& opt, Scene& scene);

/// prepareScene for a program: prints the warnings, the model's note (unless --quiet) and any
/// error; returns kGoOn, or the exit code to end with.
int prepare(const Options& opt, Prepared& out, AssetCache* assets = nullptr);

/// How a render samples and cleans its image, from the options and the scene
/// (docs/clean-images.md).
struct SamplingPlan {
    int spp = 1;           ///< A fixed count: --spp, else the scene's `spp`, else 1.
    int maxSpp = 1;        ///< Adaptive sampling's cap: --spp, else kAdaptiveMaxSpp.
    double threshold = 0;  ///< > 0: adaptive sampling to this noise.
    double seconds = 0;    ///< A time budget (--time, or a model's default); 0: none.
    bool denoise = false;
    bool studio = false;         ///< A model in the studio look (not --integrator whitted).
    bool modelDefaults = false;  ///< Neither samples, time nor threshold given for a model.
};

/// The plan `opt` asks for of the prepared scene. A model given no sample count, time or
/// threshold is sampled until clean (kModelNoiseThreshold), within kModelSeconds when
/// `timeBudgets` (glint; glint-mpi renders without), and denoised; scenes are not denoised
/// unless asked. Frame pieces (`piece`) take exactly what they are told, and are never denoised.
SamplingPlan planSampling(const Options& opt, const Prepared& prepared, bool piece,
                          bool timeBudgets);

/// A render as a SamplingPlan asks, and what it cost.
struct Rendered {
    RenderResult result;
    double buildSeconds = 0;     ///< Building the BVHs (0 for a scene prepared before).
    double denoiseSeconds = 0;   ///< 0: not denoised.
    FilmDenoiseReport denoised;  ///< What the denoiser did, if it ran.
};

/// The denoiser that --denoiser and --denoise-quality name (checked when parsed).
FilmDenoiseOptions filmDenoiseOptions(const std::string& denoiser, const std::string& quality);
/// Why --denoiser cannot be had in this build ("--denoiser oidn" without the network's
/// weights), or "" (a usage error, exit 2, before anything is rendered).
std::string denoiserProblem(const std::string& denoiser, const std::string& quality);

/// What to tell a user whose image came out almost black (the mean luminance, exposed, below
/// 0.001 of white: a camera inside a closed sky dome, a file with no lights): why, and what to
/// try; "" for any other image.
std::string darkImageWarning(const Film& film, const DisplayTransform& display);

/// "glint: warning: ..." (with `program`'s name) if the denoiser met values that were not
/// finite; nothing otherwise.
void warnNonFinite(const char* program, const FilmDenoiseReport& report);

/// Renders the prepared scene as `plan` says: builds its BVHs unless it is prepared already
/// (refitting `accel`'s where they fit), then samples adaptively, to a time budget or a fixed
/// count, with `ro`'s pool, seed, cancel flag, progress and piece settings (spp and passes are
/// set here: the passes when `aovs` or the plan denoises), and denoises a complete image when
/// the plan asks. Shared by glint and the Python module, so that both render the same pixels.
Rendered renderPlanned(const Options& opt, Prepared& prepared, const SamplingPlan& plan,
                       RenderOptions ro, bool aovs, FrameAccel* accel = nullptr);

/// How glint merge and glint denoise show their image, as their options change it
/// (options.cpp registers them).
struct DisplayOptions {
    std::optional<double> exposure;  ///< --exposure EV
    int srgb = 0;                    ///< --srgb 1, --no-srgb -1, 0 not given
    std::string toneMap;             ///< --tonemap NAME; empty: not given

    /// `base` with what was given in its place.
    DisplayTransform over(DisplayTransform base) const;
};

int usageError(const std::string& message);
double secondsSince(std::chrono::steady_clock::time_point t);
/// "1 light", "2 lights".
std::string count(unsigned long long n, const char* one, const char* many);
std::string primitiveSummary(const Primitives& prims);
/// "maxdepth 12", with the limits by kind where there are any: "maxdepth 12 (diffuse 8, glossy
/// 8, transmission 12, volume 8)".
std::string depthSummary(const Scene& scene);
void printStats(const Scene& scene, double parse, double build, const RenderResult& r,
                double write);

}  // namespace glint::cli
