// glint: the command-line renderer. Usage errors exit 2, scene and render errors exit 1.

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

#include "cli.h"
#include "demo_scene.h"
#include "denoise.h"
#include "glint/core/atomic_file.h"
#include "glint/core/error.h"
#include "glint/core/input_log.h"
#include "glint/core/parallel.h"
#include "glint/core/system.h"
#include "glint/io/image/exr_piece.h"
#include "glint/io/image/image_io.h"
#include "glint/render/progress.h"
#include "glint/render/renderer.h"
#include "merge.h"
#include "options.h"
#include "piece.h"

namespace {

using namespace glint::cli;

// Interrupts. The first SIGINT or SIGTERM asks the render to stop: workers finish their
// current block, what is done is written (atomically) and marked partial, and glint exits
// with 128 + the signal (130, 143). A second one leaves at once, removing any half-written
// temporary file; the output file itself is never touched then.
std::atomic<bool> gStop{false};
volatile std::sig_atomic_t gSignal = 0;

extern "C" void onSignal(int sig) {
    if (gStop.load()) {
        if (const char* tmp = glint::pendingTempFile()) ::unlink(tmp);
        ::_exit(128 + sig);
    }
    gSignal = sig;
    gStop.store(true);
}

void installSignalHandlers() {
    struct sigaction sa {};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

const char* signalName(int sig) { return sig == SIGTERM ? "SIGTERM" : "SIGINT"; }

/// Renders the one frame `opt` asks for; `assets` keeps model files, and `accel` the BVHs, for
/// the next frame of a sequence (null: none follows).
int run(const Options& opt, glint::AssetCache* assets = nullptr,
        glint::FrameAccel* accel = nullptr) {
    using Clock = std::chrono::steady_clock;
    // A piece of the frame: its inputs are hashed as they are read, so that glint merge can
    // tell pieces of other scenes (or other versions of its meshes and textures) apart.
    const bool piece = wantsPiece(opt);
    if (piece)
        if (int code = checkPieceOptions(opt); code != kGoOn) return code;
    std::optional<glint::InputLog> inputs;
    if (piece) inputs.emplace();
    Prepared prepared;
    if (int code = prepare(opt, prepared, assets); code != kGoOn) return code;
    glint::PieceInfo pieceInfo;
    // Passes, denoising and adaptive sampling (docs/clean-images.md).
    const SamplingPlan plan = planSampling(opt, prepared, piece, true);
    const int spp = plan.spp, maxSpp = plan.maxSpp;
    if (piece) {
        // The demo is read from no file: its text is hashed instead.
        uint64_t hash =
            prepared.demo ? glint::hashBytes(glint::kDemoScene, inputs->hash()) : inputs->hash();
        inputs.reset();
        if (int code = describePiece(opt, prepared, opt.noiseThreshold > 0 ? maxSpp : spp, hash,
                                     pieceInfo);
            code != kGoOn)
            return code;
    }
    std::unique_ptr<glint::Scene>& scene = prepared.scene;
    const std::string& output = prepared.output;
    const bool demo = prepared.demo;
    const double parseSeconds = prepared.parseSeconds;
    const glint::DisplayTransform& display = prepared.display;
    if (opt.check) {
        const auto& prims = scene->primitives;
        std::printf("%s: ok: %dx%d, %s, %s, %s, output %s\n",
                    demo ? "demo.test" : opt.scene.c_str(), scene->width, scene->height,
                    primitiveSummary(prims).c_str(),
                    count(scene->lights.size(), "light", "lights").c_str(),
                    depthSummary(*scene).c_str(), output.c_str());
        // A model file's format extensions, each with what Glint does with it.
        if (!prepared.extensions.empty()) {
            size_t width = 0;
            for (const glint::FormatExtension& e : prepared.extensions)
                width = std::max(width, e.name.size());
            std::printf("extensions used (%zu):\n", prepared.extensions.size());
            for (const glint::FormatExtension& e : prepared.extensions)
                std::printf("  %-*s  %s\n", static_cast<int>(width), e.name.c_str(),
                            e.support.c_str());
        }
        // A model file's animations, as --animation names them.
        if (!prepared.animations.empty()) {
            std::printf("animations (%zu):\n", prepared.animations.size());
            for (size_t i = 0; i < prepared.animations.size(); ++i) {
                const glint::ModelAnimation& a = prepared.animations[i];
                std::printf("  %zu  %s  %g to %g s (frames %.0f to %.0f at %g fps), %zu %s\n", i,
                            a.name.empty() ? "(unnamed)" : ("'" + a.name + "'").c_str(), a.start,
                            a.end, std::floor(a.start * opt.fps), std::ceil(a.end * opt.fps),
                            opt.fps, a.channels, a.channels == 1 ? "channel" : "channels");
            }
        }
        return 0;
    }

    if (gStop.load()) {
        std::fprintf(stderr, "glint: %s before rendering: nothing written\n", signalName(gSignal));
        return 128 + gSignal;
    }

    // The image is the one large allocation left: refuse what the machine cannot hold.
    double filmBytes = static_cast<double>(scene->width) * scene->height * sizeof(glint::Vec3);
    if (size_t available = glint::availableMemoryBytes();
        available > 0 && filmBytes > static_cast<double>(available)) {
        std::fprintf(stderr,
                     "glint: error: a %dx%d image needs %s of memory, more than the %s available\n",
                     scene->width, scene->height, glint::formatBytes(filmBytes).c_str(),
                     glint::formatBytes(static_cast<double>(available)).c_str());
        return kExitSceneError;
    }

    glint::AovSelection aovs;
    if (!opt.aov.empty()) parseAovList(opt.aov, aovs);  // checked with the options
    if (aovs.any() && !piece && glint::imageFormatFor(output) != glint::ImageFormat::Exr)
        return usageError("--aov writes the passes as layers of an OpenEXR file: '" + output +
                          "' is not an .exr file");
    const double threshold = plan.threshold, budget = plan.seconds;
    const bool studio = plan.studio, modelDefaults = plan.modelDefaults;

    // Build, then render, on one pool of threads (-t 1: the calling thread alone).
    glint::ThreadPool pool(opt.threads);
    glint::ProgressReporter progress(stderr, ::isatty(STDERR_FILENO) == 1);
    glint::RenderOptions ro;
    ro.pool = &pool;
    ro.seed = opt.seed;
    ro.cancel = &gStop;
    if (piece) renderPieceWith(pieceInfo, ro);
    if (!opt.quiet) ro.onProgress = [&](const glint::RenderProgress& p) { progress.update(p); };
    Rendered rendered = renderPlanned(opt, prepared, plan, ro, aovs.any(), accel);
    glint::RenderResult& result = rendered.result;
    const double buildSeconds = rendered.buildSeconds;
    if (!opt.quiet)
        progress.finish(
            {0, 0, result.seconds}, result.complete,
            (opt.timeBudget > 0 || threshold > 0) && result.complete ? result.samplesPerPixel : 0);
    if (!opt.quiet && threshold > 0 && result.complete)
        std::fprintf(stderr,
                     "glint: adaptive sampling%s: %.0f samples per pixel on average (most %d of "
                     "%d), %.0f%% of pixels below noise %g%s\n",
                     modelDefaults ? " (a model's default)" : "", result.meanSamplesPerPixel,
                     result.samplesPerPixel, maxSpp, 100 * result.converged, threshold,
                     budget > 0 ? (", within " + glint::formatSeconds(budget)).c_str() : "");

    if (piece && !result.complete) {
        // A piece is whole or not at all: glint merge would refuse a partial one.
        std::fprintf(stderr, "glint: %s: stopped early; no piece written (%d of %d tiles done)\n",
                     signalName(gSignal), result.tilesDone, result.tilesTotal);
        return 128 + gSignal;
    }

    if (rendered.denoiseSeconds > 0 && !opt.quiet)
        std::fprintf(stderr, "glint: denoised in %.2f s (%s%s)\n", rendered.denoiseSeconds,
                     rendered.denoised.method.c_str(),
                     studio && opt.denoise == 0
                         ? "; a model's default; --no-denoise for the raw image"
                         : "");
    if (rendered.denoiseSeconds > 0) warnNonFinite("glint", rendered.denoised);
    if (prepared.model && !piece && result.complete)
        if (std::string dark = darkImageWarning(result.film, display); !dark.empty())
            std::fprintf(stderr, "glint: warning: %s\n", dark.c_str());

    // Write.
    auto t2 = Clock::now();
    try {
        if (piece)
            glint::writeFileAtomically(output, glint::encodePiece(pieceInfo, result.sums));
        else
            glint::writeImage(output, result.film, display, &result.aovs, aovs);
    } catch (const glint::RenderError& e) {
        std::fprintf(stderr, "glint: error: %s\n", e.what());
        return kExitSceneError;
    }
    double writeSeconds = secondsSince(t2);
    if (!result.complete) {
        // Always said, even with -q: the file is not the whole image.
        std::fprintf(stderr,
                     "glint: %s: stopped early; wrote the partial image (%d of %d tiles, the rest "
                     "black) to %s\n",
                     signalName(gSignal), result.tilesDone, result.tilesTotal, output.c_str());
        return 128 + gSignal;
    }
    if (result.stoppedEarly) {
        // Also said with -q: the image is whole, but has fewer samples than there was time for.
        std::fprintf(stderr,
                     "glint: %s: stopped early; wrote the image of the %d passes done (%d "
                     "samples per pixel) to %s\n",
                     signalName(gSignal), result.passes, result.samplesPerPixel, output.c_str());
        return 128 + gSignal;
    }
    if (!opt.quiet && piece)
        std::fprintf(stderr, "glint: wrote %s (%s of the %dx%d frame: %lld pixels)\n",
                     output.c_str(), pieceInfo.describe().c_str(), scene->width, scene->height,
                     pieceInfo.pixelCount());
    else if (!opt.quiet)
        std::fprintf(stderr, "glint: wrote %s (%dx%d)\n", output.c_str(), scene->width,
                     scene->height);
    if (opt.stats) printStats(*scene, parseSeconds, buildSeconds, result, writeSeconds);
    if (accel) scene->keepAccel(*accel);
    return 0;  // a signal that arrived while writing is the caller's: the image is complete
}

/// Renders the frames --frames asks for, one file each, loading model files once; or the one
/// frame of the other options.
int runFrames(const Options& opt) {
    if (opt.frames.empty()) {
        int code = run(opt);
        if (code == 0 && gStop.load()) {
            std::fprintf(stderr, "glint: %s: stopped after writing the image\n",
                         signalName(gSignal));
            return 128 + gSignal;
        }
        return code;
    }
    FrameRange range;
    parseFrameRange(opt.frames, range);  // checked with the options
    std::string pattern;
    if (std::string problem = sequencePattern(opt, pattern); !problem.empty())
        return usageError(problem);
    // A piece's hash covers the files it read: each frame of pieces reads them again.
    glint::AssetCache assets;
    glint::FrameAccel accel;  // refitted from frame to frame where the geometry allows
    const bool keep = !wantsPiece(opt);
    for (long long i = 0, n = range.count(); i < n; ++i) {
        Options frame = opt;
        frame.frames.clear();
        frame.frame = range.first + i * range.step;
        frame.output = frameFileName(pattern, *frame.frame);
        frame.noteSaid = i > 0;  // the framing is the same for every frame: said once
        if (!opt.quiet)
            std::fprintf(stderr, "glint: frame %lld (%lld of %lld)\n", *frame.frame, i + 1, n);
        if (int code = run(frame, keep ? &assets : nullptr, &accel); code != 0) return code;
        if (gStop.load()) {
            std::fprintf(stderr, "glint: %s: stopped after frame %lld\n", signalName(gSignal),
                         *frame.frame);
            return 128 + gSignal;
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    // `glint merge ...`: the one subcommand (a scene file named merge is ./merge).
    if (argc > 1 && std::string_view(argv[1]) == "merge") return mergeMain(argc - 1, argv + 1);
    if (argc > 1 && std::string_view(argv[1]) == "denoise") return denoiseMain(argc - 1, argv + 1);
    Options opt;
    if (int code = parseOptions(argc, argv, opt); code != kGoOn) return code;
    installSignalHandlers();
    try {
        return runFrames(opt);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint: error: %s\n", e.what());
        return kExitSceneError;
    }
}
