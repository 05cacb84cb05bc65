#include "glint/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "glint/core/error.h"
#include "glint/core/parallel.h"
#include "glint/render/film/sampler.h"

namespace glint {

namespace {

constexpr double kReportSeconds = 0.1;  // progress about ten times a second

/// The tiles of part `part` of `parts`: the image's grid of `tile`-pixel tiles, every
/// parts-th row of it from the top, each tile clipped to `crop`.
std::vector<PixelBounds> partTiles(const PixelBounds& crop, int tile, int parts, int part) {
    std::vector<PixelBounds> tiles;
    for (int y0 = crop.y0 - crop.y0 % tile; y0 < crop.y1; y0 += tile) {
        if ((y0 / tile) % parts != part) continue;
        for (int x0 = crop.x0 - crop.x0 % tile; x0 < crop.x1; x0 += tile)
            tiles.push_back({std::max(x0, crop.x0), std::min(x0 + tile, crop.x1),
                             std::max(y0, crop.y0), std::min(y0 + tile, crop.y1)});
    }
    return tiles;
}

}  // namespace

FilmLayout filmLayout(const Scene& scene, const RenderOptions& options) {
    FilmLayout l;
    PixelBounds crop =
        options.crop.empty() ? PixelBounds{0, scene.width, 0, scene.height} : options.crop;
    l.crop = {std::max(crop.x0, 0), std::min(crop.x1, scene.width), std::max(crop.y0, 0),
              std::min(crop.y1, scene.height)};
    const bool cropped = options.cropFilm && !options.crop.empty();
    l.ox = cropped ? l.crop.x0 : 0;
    l.oy = cropped ? l.crop.y0 : 0;
    l.width = cropped ? std::max(l.crop.x1 - l.crop.x0, 0) : scene.width;
    l.height = cropped ? std::max(l.crop.y1 - l.crop.y0, 0) : scene.height;
    return l;
}

RenderResult render(const Scene& scene, const RenderOptions& options) {
    using Clock = std::chrono::steady_clock;
    auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

    // ==== 1. What every sample needs: camera, integrator, sample positions, random numbers ====
    RenderResult result;
    const Camera camera(*scene.camera, scene.width, scene.height);
    std::unique_ptr<Integrator> ownIntegrator;
    if (!options.integrator) ownIntegrator = makeIntegrator(scene, {options.spp});
    const Integrator* integrator = options.integrator ? options.integrator : ownIntegrator.get();
    const PixelSampler sampler(options.spp, options.seed, scene.filter,
                               options.progressivePositions);
    // A scene where something moves: each camera sample has its own shutter time, drawn
    // first from its random numbers, and its camera rays go one by one (a packet's would
    // share one time).
    const bool moving = scene.moves();
    const bool movingCamera = scene.cameraMotion.size() > 1;
    // Per-sample random numbers only where something draws them.
    const bool seeded = camera.hasLens() || integrator->usesRandomNumbers() || moving;
    const int spp = sampler.samplesPerPixel();
    const int sampleBegin = std::clamp(options.sampleBegin, 0, spp);
    const int sampleEnd =
        options.sampleEnd > 0 ? std::clamp(options.sampleEnd, sampleBegin, spp) : spp;
    const double rendered = sampleEnd - sampleBegin;  // samples per pixel of this part

    // ==== 2. Where the pixels go: the film (or the caller's, or sums to add into) ====
    const int tile = std::max(1, options.tileSize);
    const FilmLayout layout = filmLayout(scene, options);
    const PixelBounds crop = layout.crop;
    const int ox = layout.ox, oy = layout.oy;
    const int filmWidth = layout.width, filmHeight = layout.height;
    // Or the caller's film, of that size, reused across calls (the web page's).
    if (options.film &&
        (options.film->width() != filmWidth || options.film->height() != filmHeight))
        throw RenderError("the film to render into is " + std::to_string(options.film->width()) +
                          "x" + std::to_string(options.film->height()) + ", not " +
                          std::to_string(filmWidth) + "x" + std::to_string(filmHeight));
    FilmSums* const accumulate = options.accumulate;
    if (accumulate && (accumulate->width() != filmWidth || accumulate->height() != filmHeight))
        throw RenderError("the sums to add into are not the film's size");
    const std::vector<uint8_t>* const active = accumulate ? options.active : nullptr;
    if (active && active->size() != static_cast<size_t>(filmWidth) * filmHeight)
        throw RenderError("the mask of pixels to render is not the film's size");
    if (!options.film && !accumulate) result.film = Film(filmWidth, filmHeight);
    Film& film = options.film ? *options.film : result.film;
    if (options.keepSums) result.sums = FilmSums(filmWidth, filmHeight);
    const bool passes = options.aovs || (accumulate && accumulate->hasPasses());
    if (options.aovs && !accumulate) {
        result.aovs = RenderPasses(filmWidth, filmHeight);
        if (options.keepSums) result.sums.keepPasses();
    }

    // ==== 3. Which tiles: the part's, of the range asked for ====
    const std::vector<PixelBounds> tiles =
        partTiles(crop, tile, std::max(options.parts, 1), options.part);
    // Of those, tiles [firstTile, firstTile + tileCount) only (the web page's calls).
    const int firstTile = std::clamp(options.firstTile, 0, static_cast<int>(tiles.size()));
    const int available = static_cast<int>(tiles.size()) - firstTile;
    const int tilesTotal =
        options.tileCount < 0 ? available : std::min(options.tileCount, available);
    std::atomic<int> nextTile{0}, tilesDone{0};  // counted from firstTile

    // ==== 4. One block of 4 x 2 pixels: camera rays, their hits, the integrator, the film ====
    // Camera rays go in packets of eight: 4 x 2 pixels at one sample per pixel, or eight
    // samples of one pixel. Each pixel still sums its samples in the sampler's order. Shadow
    // and mirror rays go one by one: they start on the surfaces, often in different leaves of
    // dense meshes, and packets of them measured up to 2x slower (docs/performance.md).
    struct Sample {
        int pixel;  ///< Index within the block.
        Ray ray;
        Rng rng;                 ///< The sample's own random numbers, after the lens's.
        uint32_t index = 0;      ///< Within the pixel.
        uint64_t pixelSeed = 0;  ///< Of its pixel (seeded samples only).
        float time = 0;          ///< On the shutter, 0 to 1 (scenes that move only).
    };
    // Light the integrator traces in a pass of its own, for the whole image (the path
    // tracer's caustics): each pixel's sum over this render's samples, added to its own.
    std::shared_ptr<const LightPassResult> lightPass;
    // The calling thread renders too, and reports progress every 100 ms: between its blocks,
    // and within a block of many samples.
    double lastReport = 0;
    auto report = [&] {
        lastReport = elapsed();
        options.onProgress({tilesDone.load(), tilesTotal, lastReport});
    };
    // Renders the block of 4 x 2 pixels at (bx, by); `reports`: on the reporting thread. A
    // block at thousands of samples per pixel takes a second or more: every 64 samples it stops,
    // writing nothing, if the render is cancelled (the tile is then not done).
    auto renderBlock = [&](int bx, int by, int x1, int y1, std::vector<Sample>& samples,
                           RayCounts& counts, bool reports) {
        // -- The block's camera samples: positions, lens, shutter time, random numbers --
        samples.clear();
        int w = std::min(4, x1 - bx), h = std::min(2, y1 - by);
        static constexpr Rng kUnseeded{};
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                if (active &&
                    !(*active)[static_cast<size_t>(by + y - oy) * filmWidth + bx + x - ox])
                    continue;
                if (!seeded) {
                    sampler.forEachSample(
                        bx + x, by + y,
                        [&](double px, double py) {
                            samples.push_back({y * 4 + x, camera.generateRay(px, py), kUnseeded});
                        },
                        sampleBegin, sampleEnd);
                    continue;
                }
                int index = sampleBegin;
                const uint64_t pixelSeed = sampler.pixelSeed(bx + x, by + y);  // once per pixel
                sampler.forEachSample(
                    bx + x, by + y,
                    [&](double px, double py) {
                        Rng rng(sampler.sampleSeed(bx + x, by + y, index++));
                        const float time = moving ? static_cast<float>(rng.uniform()) : 0.0f;
                        std::optional<Camera> atTime;
                        if (movingCamera)
                            atTime.emplace(cameraAt(scene.cameraMotion, time), scene.width,
                                           scene.height);
                        const Camera& c = atTime ? *atTime : camera;
                        Ray ray = c.hasLens() ? c.generateRay(px, py, rng.uniform(), rng.uniform())
                                              : c.generateRay(px, py);
                        samples.push_back({y * 4 + x, ray, rng, static_cast<uint32_t>(index - 1),
                                           pixelSeed, time});
                    },
                    sampleBegin, sampleEnd);
            }
        if (active && samples.empty()) return;
        // -- Packets of eight camera rays, then the integrator for each sample --
        SampleSum sum[8];  // each pixel's samples, summed exactly (film.h)
        PassSums passSums[8];
        for (size_t i = 0; i < samples.size(); i += 8) {
            if (i > 0 && i % 64 == 0) {
                if (options.cancel && options.cancel->load(std::memory_order_relaxed)) return;
                if (reports && elapsed() - lastReport >= kReportSeconds) report();
            }
            int n = static_cast<int>(std::min<size_t>(8, samples.size() - i));
            RayPacket8 packet;
            packet.active = static_cast<uint8_t>((1u << n) - 1);
            Ray rays[8];
            for (int k = 0; k < n; ++k) {
                rays[k] = samples[i + k].ray;
                packet.set(k, TraversalRay(rays[k]));
            }
            HitPacket8 hits;
            if (!moving) {
                scene.bvh().intersect8(packet, hits);
            } else {
                for (int k = 0; k < n; ++k) {
                    setShutterTime(samples[i + k].time);
                    Hit one;
                    scene.bvh().intersect(packet.rays[k], one);
                    hits.set(k, one);
                }
            }
            counts.camera += static_cast<uint64_t>(n);
            for (int k = 0; k < n; ++k) {
                Hit hit = hits[k];
                if (moving) setShutterTime(samples[i + k].time);
                bool found = hit.t < std::numeric_limits<float>::infinity();
                if (found && scene.filtersCameraHits()) [[unlikely]]
                    found = scene.filterHit(rays[k], hit, true);
                const Sample& s = samples[i + k];
                PathContext ctx{s.rng, counts};
                ctx.pixelSeed = s.pixelSeed;
                ctx.sampleIndex = s.index;
                ctx.lightPass = lightPass.get();
                if (!passes) {
                    sum[s.pixel].add(integrator->li(rays[k], found ? &hit : nullptr, ctx));
                    continue;
                }
                SamplePasses sp;
                ctx.passes = &sp;
                const Vec3 v = integrator->li(rays[k], found ? &hit : nullptr, ctx);
                sum[s.pixel].add(v);
                passSums[s.pixel].addSample(v, sp);
            }
        }
        // -- Each pixel's sum, with the light pass's share, into the film, sums or passes --
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                SampleSum s = sum[y * 4 + x];
                if (lightPass) {
                    // Its mean per sample joins each sample's value, in the squares too (the
                    // variance is the camera samples' own).
                    const Vec3 c =
                        lightPass->image[static_cast<size_t>(by + y) * scene.width + bx + x];
                    if (passes) {
                        const Vec3 mean = c * (1 / rendered);
                        passSums[y * 4 + x].squares += (s.value() * 2.0 + c) * mean;
                    }
                    s.add(c);
                }
                const int fx = bx + x - ox, fy = by + y - oy;
                if (accumulate) {
                    const size_t i = static_cast<size_t>(fy) * filmWidth + fx;
                    if (active && !(*active)[i]) continue;
                    accumulate->sum(fx, fy).add(s);
                    accumulate->weight(fx, fy) += rendered;
                    if (passes) accumulate->passes(fx, fy) += passSums[y * 4 + x];
                    continue;
                }
                const Vec3 total = s.value();
                film.at(fx, fy) = pixelValue(total, rendered);
                if (passes)
                    resolvePassesAt(total, rendered, passSums[y * 4 + x], result.aovs,
                                    result.aovs.index(fx, fy));
                if (options.keepSums) {
                    result.sums.sum(fx, fy) = s;
                    result.sums.weight(fx, fy) = rendered;
                    if (passes) result.sums.passes(fx, fy) = passSums[y * 4 + x];
                }
            }
    };

    // ==== 5. The threads: tiles handed out one at a time, until done or cancelled ====
    // Each thread counts its rays in a local and stores them once at the end: counters of two
    // threads side by side in one cache line, updated for every ray, cost 10% of the render on
    // two cores.
    auto renderTiles = [&](RayCounts& out, bool caller) {
        const bool reports = caller && options.onProgress;
        std::vector<Sample> samples;
        RayCounts counts;
        try {
            for (;;) {
                if (options.cancel && options.cancel->load(std::memory_order_relaxed)) break;
                int t = nextTile.fetch_add(1, std::memory_order_relaxed);
                if (t >= tilesTotal) break;
                const auto [x0, x1, y0, y1] = tiles[static_cast<size_t>(t + firstTile)];
                bool stopped = false;
                for (int by = y0; by < y1 && !stopped; by += 2)
                    for (int bx = x0; bx < x1; bx += 4) {
                        // Checked per block too: a tile at many samples per pixel can take long.
                        if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
                            stopped = true;
                            break;
                        }
                        if (reports && elapsed() - lastReport >= kReportSeconds) report();
                        renderBlock(bx, by, x1, y1, samples, counts, reports);
                    }
                if (stopped) break;
                tilesDone.fetch_add(1, std::memory_order_relaxed);
            }
        } catch (...) {
            nextTile.store(tilesTotal);  // the other threads stop after their current tile
            throw;
        }
        out = counts;
    };

    // ==== 6. The light pass first (the path tracer's caustics), then every thread renders ====
    std::optional<ThreadPool> ownPool;
    ThreadPool& pool = options.pool ? *options.pool : ownPool.emplace(options.threads);
    if (tilesTotal > 0 && seeded)
        lightPass =
            integrator->lightPass(sampleBegin, sampleEnd, options.seed, pool, options.cancel);
    const int threads = std::min(pool.threads(), tilesTotal);
    std::vector<RayCounts> counts(static_cast<size_t>(std::max(threads, 1)));
    {
        TaskGroup helpers(pool);
        for (int i = 1; i < threads; ++i) helpers.run([&, i] { renderTiles(counts[i], false); });
        renderTiles(counts[0], true);
        while (!helpers.waitFor(std::chrono::milliseconds(100)))
            if (options.onProgress) report();
    }
    for (const RayCounts& c : counts) result.rays += c;

    // ==== 7. What happened: rays, time, tiles ====
    result.seconds = elapsed();
    result.tilesDone = tilesDone.load();
    result.tilesTotal = tilesTotal;
    result.samplesPerPixel = sampler.samplesPerPixel();
    result.complete = result.tilesDone == tilesTotal;
    if (options.onProgress) options.onProgress({tilesDone.load(), tilesTotal, result.seconds});
    return result;
}

}  // namespace glint
