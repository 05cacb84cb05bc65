#pragma once
/// Renders a prepared scene in parallel tiles. The image does not depend on the thread count:
/// every pixel is computed independently of which thread renders it.

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "glint/render/film/film.h"
#include "glint/render/integrators/integrator.h"

namespace glint {

struct RenderProgress {
    int tilesDone = 0, tilesTotal = 0;
    double seconds = 0;  ///< Since the render started.
    /// The share of the whole job done, when the job is more than one pass over the tiles (a
    /// render to a time budget, render/progressive.h); negative: tilesDone / tilesTotal.
    double overall = -1;
    double fraction() const {
        if (overall >= 0) return overall;
        return tilesTotal ? double(tilesDone) / tilesTotal : 1.0;
    }
};

class ThreadPool;

struct RenderOptions {
    /// The threads to render on, the calling thread among them (a pool of one renders on the
    /// calling thread alone); null: a pool of `threads` made for this render.
    ThreadPool* pool = nullptr;
    int threads = 0;    ///< Threads when `pool` is null; 0 means all hardware threads.
    int tileSize = 16;  ///< Tile side in pixels.
    int spp = 1;        ///< Camera rays per pixel (stratified, jittered, the scene's filter).
    uint64_t seed = 0;  ///< Seed of the sub-pixel jitter.
    /// Called on the calling thread about ten times a second (between its blocks of 4 x 2
    /// pixels, so also during long tiles), and once at the end.
    std::function<void(const RenderProgress&)> onProgress;
    /// When set and it becomes true, every thread stops after its current block of pixels.
    const std::atomic<bool>* cancel = nullptr;

    // Part of a frame (docs/scale-out.md): the image keeps the scene's size; pixels outside
    // the part are black with weight 0 in RenderResult::sums. Every pixel and sample rendered
    // is exactly the one the whole render computes there.
    PixelBounds crop;       ///< The pixels to render; empty: the whole image.
    int part = 0;           ///< With `parts` > 1: only the rows of tiles (tileSize pixels high,
    int parts = 1;          ///< counted from the image's top) whose index % parts == part.
    int sampleBegin = 0;    ///< Samples [sampleBegin, sampleEnd) of each pixel's `spp`;
    int sampleEnd = 0;      ///< sampleEnd 0: up to spp.
    bool keepSums = false;  ///< Fill RenderResult::sums (for merging parts).
    /// Only tiles [firstTile, firstTile + tileCount) of the part (the image, numbered row by row
    /// from the top left (tileCount < 0: to the last tile); the film's other pixels stay black, and
    /// progress and the result count these tiles only. For a caller that shows the image as it
    /// forms, a few tiles per call (the web page, web/bindings/).
    int firstTile = 0, tileCount = -1;
    /// The film to render into, of the scene's width and height (the crop's with cropFilm),
    /// reused across calls (with
    /// tile ranges, a new film per call would cost more than its few tiles); RenderResult::film
    /// is then empty. Only the rendered tiles' pixels are written. Null: a new film.
    Film* film = nullptr;
    /// With a crop: the film (and sums) hold the crop's pixels only, pixel (0, 0) being the
    /// crop's (x0, y0), so that rendering a small part of a large image allocates that part
    /// only (the MPI mode renders thousands of such parts per frame, apps/mpi_*.cpp).
    bool cropFilm = false;
    /// Also make the render passes (AOVs; film.h: albedo, normal, depth, variance): into
    /// RenderResult::aovs, and into RenderResult::sums with keepSums.
    bool aovs = false;
    /// Add what each rendered pixel's samples sum to (and their pass sums, if it keeps them)
    /// into these sums, of the film's size, instead of filling RenderResult::film (left empty)
    /// and RenderResult::aovs: how a render in rounds collects its samples (adaptive.h).
    FilmSums* accumulate = nullptr;
    /// With `accumulate`: the film's pixels to render (non-zero), row by row; null: all.
    const std::vector<uint8_t>* active = nullptr;
    /// Sub-pixel positions that are spread in every prefix of a pixel's samples (sampler.h),
    /// for a render that may stop a pixel after any of them; false: the stratified grid.
    bool progressivePositions = false;
    /// The integrator to render with, made by makeIntegrator for this scene and `spp`, shared
    /// by renders of many small parts (making one scans the scene's emissive primitives);
    /// null: one made for this render.
    const Integrator* integrator = nullptr;
};

struct RenderResult {
    Film film;
    FilmSums sums;      ///< With RenderOptions::keepSums: the sums and weights behind `film`.
    RenderPasses aovs;  ///< With RenderOptions::aovs: the film's render passes.
    RayCounts rays;
    double seconds = 0;
    bool complete = true;  ///< False if cancelled before every tile was rendered.
    int tilesDone = 0, tilesTotal = 0;
    /// Camera samples per pixel in the image, and the passes they were rendered in (more than
    /// one only for a render to a time budget, render/progressive.h).
    int samplesPerPixel = 0, passes = 1;
    /// An adaptive render's (adaptive.h): the mean samples per pixel, and the share of pixels
    /// that stopped below the noise threshold (the rest reached the cap or the time).
    double meanSamplesPerPixel = 0, converged = 0;
    /// A render to a time budget that was cancelled: the image is whole (every pass in it was
    /// finished) but has fewer samples than there was time for.
    bool stoppedEarly = false;
};

/// Where render() puts what it renders: the pixels asked for (options.crop clipped to the
/// image; the whole image without a crop), and the film they go into, of the image's size or,
/// with cropFilm, of the crop's, its pixel (0, 0) the image's (ox, oy).
struct FilmLayout {
    PixelBounds crop;
    int ox = 0, oy = 0;
    int width = 0, height = 0;
};
FilmLayout filmLayout(const Scene& scene, const RenderOptions& options);

/// Renders `scene` (prepared, with a camera) at its width and height with the integrator it
/// names (Scene::integrator). Throws RenderError if there is no such integrator.
RenderResult render(const Scene& scene, const RenderOptions& options);

}  // namespace glint
