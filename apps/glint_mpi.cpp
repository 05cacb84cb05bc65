// glint-mpi: glint across the ranks of an MPI job, `mpirun -np N glint-mpi SCENE [options]`,
// with glint's options and the same image, byte for byte (docs/scale-out.md, "MPI"); with
// --frames, a sequence of such frames in one job, one after the other.
//
// Every rank loads the scene itself from the filesystem they share and rank 0 checks that they
// all hold the same one (mpi_load.cpp); rank 0 then hands out tiles on demand, every rank
// rendering them on its own threads, rank 0 too, and gathers their pixels (mpi_render.cpp);
// rank 0 writes the image, atomically, once every tile is in. A rank that fails ends the job
// with one message naming it, and no image. Usage errors exit 2, scene and render errors 1, a
// signal 128 + its number.

#include <mpi.h>
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "cli.h"
#include "glint/core/atomic_file.h"
#include "glint/core/error.h"
#include "glint/core/parallel.h"
#include "glint/denoise/film_denoise.h"
#include "glint/io/image/image_io.h"
#include "glint/render/integrators/integrator.h"
#include "mpi_load.h"
#include "mpi_protocol.h"
#include "mpi_render.h"
#include "mpi_report.h"
#include "options.h"

namespace {

using namespace glint::cli;
using glint::mpi::Job;

// Interrupts. A first SIGINT or SIGTERM (mpirun passes what it gets on to every rank as
// SIGTERM) asks every rank to stop after its current block of pixels: nothing is written. A
// second one leaves at once, removing any half-written temporary file.
std::atomic<int> gInterrupt{0};

extern "C" void onSignal(int sig) {
    if (gInterrupt.load() != 0) {
        if (const char* tmp = glint::pendingTempFile()) ::unlink(tmp);
        ::_exit(128 + sig);
    }
    gInterrupt.store(sig);
}

void installSignalHandlers() {
    struct sigaction sa {};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

const char* signalName(int sig) { return sig == SIGTERM ? "SIGTERM" : "SIGINT"; }

/// glint-mpi's own options, beside glint's.
struct MpiOptions {
    int tileSide = glint::mpi::kTileSide;
    std::string timings;
};

/// Renders the one frame `opt` asks for with every rank; `assets` keeps this rank's model files,
/// and `accel` its BVHs, for the next frame of a sequence (null: none follows). Returns on rank
/// 0 the exit code, on the others 0 (rank 0 speaks for the job).
int run(const Options& opt, const MpiOptions& mpiOpt, Job& job, glint::AssetCache* assets = nullptr,
        glint::FrameAccel* accel = nullptr) {
    using Clock = std::chrono::steady_clock;
    const bool root = job.rank == 0;
    Prepared prepared;
    if (int code = glint::mpi::loadEverywhere(opt, prepared, job, assets); code != kGoOn)
        return root ? code : 0;  // rank 0 said why and ends the job with its code
    glint::Scene& scene = *prepared.scene;
    // However the frame ends, its BVHs go to the next (refitted there where they fit).
    struct KeepAccel {
        glint::Scene& scene;
        glint::FrameAccel* accel;
        ~KeepAccel() {
            if (accel) scene.keepAccel(*accel);
        }
    } keep{scene, accel};
    if (opt.check) {
        if (root)
            std::printf("%s: ok: %dx%d, %s, %s, %s, output %s, %d ranks\n",
                        prepared.demo ? "demo.test" : opt.scene.c_str(), scene.width, scene.height,
                        primitiveSummary(scene.primitives).c_str(),
                        count(scene.lights.size(), "light", "lights").c_str(),
                        depthSummary(scene).c_str(), prepared.output.c_str(), job.size);
        return 0;
    }

    // Build: on every rank, on all its threads.
    glint::mpi::RankWork work;
    work.threads = job.threads;
    work.tileSide = mpiOpt.tileSide;
    {
        auto t0 = Clock::now();
        try {
            glint::ThreadPool pool(job.threads);
            scene.prepare({&pool, prepared.kernels, accel});
        } catch (const std::exception& e) {
            work.buildError = e.what();
        }
        work.buildSeconds = secondsSince(t0);
    }
    // As glint samples and cleans, without a time budget (docs/scale-out.md, "MPI"): adaptive
    // tiles make the whole frame's pixels, and their passes are gathered for --aov and the
    // denoiser, which runs on rank 0.
    const SamplingPlan plan = planSampling(opt, prepared, false, false);
    glint::AovSelection aovs;
    if (!opt.aov.empty()) parseAovList(opt.aov, aovs);  // checked with the options
    if (aovs.any() && glint::imageFormatFor(prepared.output) != glint::ImageFormat::Exr) {
        if (root)
            usageError("--aov writes the passes as layers of an OpenEXR file: '" + prepared.output +
                       "' is not an .exr file");
        return root ? kExitUsage : 0;
    }
    work.options.spp = plan.threshold > 0 ? plan.maxSpp : plan.spp;
    work.options.seed = opt.seed;
    work.options.aovs = aovs.any() || plan.denoise;
    if (plan.threshold > 0) work.adaptive = {plan.threshold, opt.minSpp, plan.maxSpp, 0};
    // One integrator for every tile of this rank (making one scans the scene's lights).
    std::unique_ptr<glint::Integrator> integrator;
    if (work.buildError.empty()) {
        try {
            integrator = glint::makeIntegrator(scene, {work.options.spp});
            work.options.integrator = integrator.get();
        } catch (const std::exception& e) {
            work.buildError = e.what();
        }
    }

    if (!root) {
        glint::mpi::serve(scene, work, job, gInterrupt);
        MPI_Barrier(MPI_COMM_WORLD);
        return 0;
    }

    // Rank 0: render with every rank, then write once every rank has come through.
    glint::ProgressReporter progress(stderr, ::isatty(STDERR_FILENO) == 1);
    glint::Film film(scene.width, scene.height);
    glint::RenderPasses passes;
    if (work.options.aovs) passes = glint::RenderPasses(scene.width, scene.height);
    glint::mpi::FrameFigures figures;
    int code = glint::mpi::coordinate(scene, work, job, gInterrupt, film, passes, figures,
                                      opt.quiet ? nullptr : &progress);
    MPI_Barrier(MPI_COMM_WORLD);
    if (code == glint::mpi::kInterrupted) {
        int sig = gInterrupt.load();
        std::fprintf(stderr, "glint-mpi: %s: stopped; no image written\n", signalName(sig));
        return 128 + sig;
    }
    if (code != kGoOn) return code;

    if (plan.denoise) {
        auto t = Clock::now();
        glint::ThreadPool pool(job.threads);
        glint::FilmDenoiseReport report;
        film = glint::denoiseFilm(film, passes, pool,
                                  filmDenoiseOptions(opt.denoiser, opt.denoiseQuality), &report);
        if (!opt.quiet)
            std::fprintf(stderr, "glint-mpi: denoised in %.2f s (%s)\n", secondsSince(t),
                         report.method.c_str());
        warnNonFinite("glint-mpi", report);
    }
    auto t1 = Clock::now();
    try {
        glint::writeImage(prepared.output, film, prepared.display, &passes, aovs);
    } catch (const glint::RenderError& e) {
        std::fprintf(stderr, "glint-mpi: error: %s\n", e.what());
        return kExitSceneError;
    }
    double writeSeconds = secondsSince(t1);
    if (!opt.quiet)
        std::fprintf(stderr, "glint-mpi: wrote %s (%dx%d, %d ranks)\n", prepared.output.c_str(),
                     scene.width, scene.height, job.size);
    if (opt.stats)
        glint::mpi::printMpiStats(scene, prepared.parseSeconds, work, job, figures, writeSeconds);
    if (!mpiOpt.timings.empty()) {
        try {
            glint::mpi::writeTimings(mpiOpt.timings, scene, work, job, figures, writeSeconds);
        } catch (const glint::RenderError& e) {
            std::fprintf(stderr, "glint-mpi: error: --timings: %s\n", e.what());
            return kExitSceneError;
        }
    }
    return 0;  // a signal that arrived while writing is the caller's: the image is complete
}

/// Rank 0's `code` to every rank. The others wait for it sleeping: MPI's blocking collectives
/// spin, and between frames they wait while rank 0 denoises and writes the image, which a
/// spinning rank on the same machine would slow.
void shareFromRoot(int& code) {
    MPI_Request request;
    MPI_Ibcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
    for (int done = 0;;) {
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (done) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

/// Renders the frames --frames asks for, one file each, as glint does: every rank keeps the
/// model files it parsed for the next frame, and mpirun's start and MPI's set-up are paid once
/// for the sequence. Or the one frame of the other options (--frame, --time-at, or none).
int runFrames(const Options& opt, const MpiOptions& mpiOpt, Job& job) {
    const bool root = job.rank == 0;
    if (opt.frames.empty()) {
        int code = run(opt, mpiOpt, job);
        if (int sig = gInterrupt.load(); root && code == 0 && sig != 0) {
            std::fprintf(stderr, "glint-mpi: %s: stopped after writing the image\n",
                         signalName(sig));
            return 128 + sig;
        }
        return code;
    }
    FrameRange range;
    parseFrameRange(opt.frames, range);  // checked with the options
    std::string pattern;
    if (std::string problem = sequencePattern(opt, pattern); !problem.empty()) {
        if (root) usageError(problem);
        return kExitUsage;
    }
    glint::AssetCache assets;
    glint::FrameAccel accel;
    for (long long i = 0, n = range.count(); i < n; ++i) {
        Options frame = opt;
        frame.frames.clear();
        frame.frame = range.first + i * range.step;
        frame.output = frameFileName(pattern, *frame.frame);
        // --timings with a frame number in its name: a file per frame.
        MpiOptions frameMpi = mpiOpt;
        if (std::string t = frameFileName(mpiOpt.timings, *frame.frame); !t.empty())
            frameMpi.timings = t;
        if (root && !opt.quiet)
            std::fprintf(stderr, "glint-mpi: frame %lld (%lld of %lld)\n", *frame.frame, i + 1, n);
        int code = run(frame, frameMpi, job, &assets, &accel);
        // Every rank has come through the frame's last collective; only rank 0 knows whether
        // its image was written, and whether to go on: it tells the others.
        if (root && code == 0) {
            if (int sig = gInterrupt.load(); sig != 0) {
                std::fprintf(stderr, "glint-mpi: %s: stopped after frame %lld\n", signalName(sig),
                             *frame.frame);
                code = 128 + sig;
            }
        }
        shareFromRoot(code);
        if (code != 0) return root ? code : 0;
    }
    return 0;
}

/// Parses the command line on every rank (all see the same one, so all agree); rank 0 alone
/// prints help, the version or usage errors. Returns kGoOn or the exit code.
int parse(int argc, char** argv, bool root, Options& opt, MpiOptions& mpiOpt) {
    CLI::App app{
        "glint-mpi renders a scene as glint does, with the ranks of an MPI job:"
        "\n  mpirun -np N glint-mpi SCENE [options]"
        "\nEvery rank reads the scene from a filesystem they all share; rank 0 hands out"
        "\ntiles, renders too, and writes the image, byte for byte glint's. -t sets each"
        "\nrank's threads (default: the CPUs mpirun gives the rank). --frames renders a"
        "\nsequence in one job, each frame on every rank.",
        "glint-mpi"};
    app.get_formatter()->column_width(30);
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("glint-mpi: error: ") + e.what() +
               "\nRun 'glint-mpi --help' for usage.\n";
    });
    addOptions(app, opt);
    app.add_option("--tile", mpiOpt.tileSide,
                   "Side of the square tiles rank 0 hands out, 4 to 1024 pixels (default 32): "
                   "smaller ones balance many threads better, larger ones send fewer messages; "
                   "the image is the same")
        ->group("Rendering")
        ->check(CLI::Range(4, 1024))
        ->type_name("PIXELS");
    app.add_option("--timings", mpiOpt.timings,
                   "Write what rank 0 measured as JSON: every tile's render time and rank, each "
                   "rank's load and build times, the bytes sent (bench/mpi_model.py)")
        ->group("Information")
        ->type_name("FILE");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (!root) return e.get_exit_code() == 0 ? 0 : kExitUsage;
        int code = app.exit(e);
        return code == 0 ? 0 : kExitUsage;
    }
    if (opt.timeBudget > 0) {
        if (root)
            usageError("--time is not available in glint-mpi (every rank renders a fixed --spp)");
        return kExitUsage;
    }
    if (!opt.part.empty() || !opt.crop.empty() || !opt.samples.empty()) {
        if (root)
            usageError(
                "--part, --crop and --samples write frame pieces for glint merge: glint-mpi "
                "renders whole frames (render pieces with glint)");
        return kExitUsage;
    }
    if (!root) mpiOpt.timings.clear();
    return kGoOn;
}

}  // namespace

int main(int argc, char** argv) {
    int provided = 0;
    // Only the main thread of each rank calls MPI; render threads do not.
    if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        std::fprintf(stderr, "glint-mpi: error: MPI_Init failed\n");
        return kExitSceneError;
    }
    Job job;
    MPI_Comm_rank(MPI_COMM_WORLD, &job.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &job.size);
    Options opt;
    MpiOptions mpiOpt;
    int code = parse(argc, argv, job.rank == 0, opt, mpiOpt);
    if (code == kGoOn) {
        job.threads = opt.threads > 0 ? opt.threads : glint::mpi::availableCpus();
        installSignalHandlers();
        try {
            code = runFrames(opt, mpiOpt, job);
        } catch (const std::exception& e) {
            // Past the load check every rank's failures go to rank 0 as messages; this is for
            // what is left (an MPI error, memory for the image): end the job from here.
            std::fprintf(stderr, "glint-mpi: rank %d: error: %s\n", job.rank, e.what());
            MPI_Abort(MPI_COMM_WORLD, kExitSceneError);
        }
    }
    MPI_Finalize();
    return code;
}
