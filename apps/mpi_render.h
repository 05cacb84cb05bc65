#pragma once
// glint-mpi's second phase: rank 0 hands out tiles on demand and gathers their pixels; every
// rank, rank 0 included, renders tiles on its own threads (docs/scale-out.md, "MPI").

#include <atomic>
#include <string>
#include <vector>

#include "glint/render/adaptive.h"
#include "glint/render/film/film.h"
#include "glint/render/progress.h"
#include "glint/render/renderer.h"
#include "mpi_load.h"

namespace glint::mpi {

/// One tile's render, for the scaling model (bench/mpi_model.py).
struct TileTime {
    PixelBounds bounds;
    int rank = 0;
    double seconds = 0;
};

/// What rank 0 measured of a frame.
struct FrameFigures {
    double seconds = 0;  ///< From the first tile handed out to the last one in.
    RayCounts rays;      ///< Of every rank.
    int tiles = 0;
    double bytesToRoot = 0, bytesFromRoot = 0;  ///< Messages during the render.
    double coordinatorCpuSeconds = 0;           ///< Of rank 0's MPI thread.
    double receiveSeconds = 0;  ///< Rank 0's MPI thread receiving messages and placing pixels.
    std::vector<double> buildSeconds;  ///< Per rank.
    std::vector<TileTime> tileTimes;
};

/// How a rank renders its tiles: the options of a whole-frame render (spp, seed; its pool and
/// crop are ignored), its render threads, and the outcome of its BVH build.
struct RankWork {
    RenderOptions options;  ///< options.aovs: the tiles' passes are gathered too.
    AdaptiveOptions adaptive{.threshold = 0};  ///< Threshold above 0: each tile adaptively.
    int threads = 1;
    int tileSide = 32;  ///< Of the tiles rank 0 hands out.
    double buildSeconds = 0;
    std::string buildError;  ///< Non-empty: this rank's build (or integrator) failed: it
                             ///< renders nothing.
};

/// From coordinate(): a signal arrived before every tile was in.
constexpr int kInterrupted = -2;

/// Rank 0: renders `scene` into `film` (its size; and its passes into `aovs`, of that size, when
/// work.options.aovs) with every rank of the job, `interrupt` (a signal
/// number, when not 0) asking it to stop. Returns cli::kGoOn when every tile is in, kInterrupted
/// when stopped; else prints one message naming the rank that failed and returns the exit code.
/// Every worker has stopped when it returns.
int coordinate(const Scene& scene, const RankWork& work, const Job& job,
               const std::atomic<int>& interrupt, Film& film, RenderPasses& aovs,
               FrameFigures& figures, ProgressReporter* progress);

/// Every other rank: renders the tiles rank 0 hands out until it says stop. Returns 0.
int serve(const Scene& scene, const RankWork& work, const Job& job,
          const std::atomic<int>& interrupt);

}  // namespace glint::mpi
