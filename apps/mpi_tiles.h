#pragma once
// A rank's render threads in glint-mpi: each takes a tile, renders it alone into the tile's own
// film (RenderOptions crop and cropFilm, a pool of one thread), hands the pixels over, and takes
// the next, until there are none or it is cancelled. One tile per thread rather than one tile
// over all threads: no thread waits for the others to finish a tile.

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

#include "glint/core/parallel.h"
#include "glint/render/adaptive.h"
#include "glint/render/renderer.h"

namespace glint::mpi {

/// A tile handed out: its number in frameTiles() and its pixels.
struct Tile {
    int index = -1;
    PixelBounds bounds;
};

/// Where the render threads and the rank's MPI thread meet: one lock, and the news for the MPI
/// thread (a tile done, a thread ended), which waits for it on `news`.
struct Mailbox {
    std::mutex mutex;
    std::condition_variable news;     ///< For the MPI thread.
    std::condition_variable arrived;  ///< For render threads waiting for a tile.
};

/// The doubles per pixel of a tile's message: its colour, then with `passes` its render passes
/// (albedo, normal, depth, variance).
inline size_t tileValues(bool passes) { return passes ? 16 : 3; }

/// The pixels of a tile's render `r` (the tile's own size, cropFilm) as doubles, tileValues()
/// per pixel, rows from the top.
std::vector<double> tilePixels(const RenderResult& r, bool passes);

/// Places a tile's pixels (as tilePixels made them) at `bounds` of `film` and, with passes,
/// of `aovs` (the frame's size).
void placeTile(const double* pixels, const PixelBounds& bounds, Film& film, RenderPasses* aovs);

class TileRenderers {
  public:
    /// Called with the mailbox locked: the next tile, or nothing to end the thread. May wait on
    /// `mailbox.arrived` (cancel() wakes it, and sets the flag it is given).
    using Take = std::function<std::optional<Tile>(std::unique_lock<std::mutex>&,
                                                   const std::atomic<bool>& cancelled)>;
    /// Called without the lock, on the render thread, for each tile rendered completely.
    using Deliver = std::function<void(const Tile&, RenderResult&&, double seconds)>;

    /// Starts `threads` render threads (none if 0), rendering each tile with `options`, or
    /// adaptively with `adaptive` when its threshold is above 0.
    TileRenderers(const Scene& scene, const RenderOptions& options, const AdaptiveOptions& adaptive,
                  int threads, Mailbox& mailbox, Take take, Deliver deliver);
    /// Cancels and waits.
    ~TileRenderers();
    TileRenderers(const TileRenderers&) = delete;
    TileRenderers& operator=(const TileRenderers&) = delete;

    /// Asks every thread to stop after its current block of pixels; wakes waiting ones.
    void cancel();
    const std::atomic<bool>& cancelled() const { return cancel_; }
    /// Whether every thread has ended (call with the mailbox locked).
    bool finished() const { return running_ == 0; }
    /// The first exception a thread threw, as text (call with the mailbox locked).
    const std::string& error() const { return error_; }
    /// Waits for every thread to end.
    void wait();

  private:
    void loop();

    const Scene& scene_;
    RenderOptions options_;
    AdaptiveOptions adaptive_;
    Mailbox& mailbox_;
    Take take_;
    Deliver deliver_;
    std::atomic<bool> cancel_{false};
    int running_ = 0;    // guarded by the mailbox's lock
    std::string error_;  // guarded by the mailbox's lock
    ThreadPool pool_;    // threads + 1: the MPI thread is the pool's caller, rendering nothing
    TaskGroup group_;
};

}  // namespace glint::mpi
