#include "glint/render/adaptive.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "glint/render/integrators/integrator.h"
#include "glint/render/progressive.h"

namespace glint {

double pixelError(const Vec3& sum, const Vec3& squares, double n) {
    if (!(n >= 2)) return std::numeric_limits<double>::infinity();
    const Vec3 mean = sum * (1.0 / n);
    double noise = 0;
    for (int c = 0; c < 3; ++c) {
        const double variance = (squares[c] / n - mean[c] * mean[c]) / (n - 1);
        noise += variance > 0 ? std::sqrt(variance) : 0;
    }
    const double brightness = std::max(mean.x + mean.y + mean.z, 0.0);
    return noise / (1e-4 + std::sqrt(brightness));
}

RenderResult renderAdaptive(const Scene& scene, const RenderOptions& options,
                            const AdaptiveOptions& adaptive) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const int maxSpp = std::max(adaptive.maxSpp, 1);
    const int minSpp =
        std::clamp(adaptive.minSpp > 0 ? adaptive.minSpp : kDefaultMinSpp, 1, maxSpp);

    const FilmLayout layout = filmLayout(scene, options);
    const int width = layout.width, height = layout.height;
    FilmSums sums(width, height);
    sums.keepPasses();  // the squares, for the error; the other passes come along
    std::vector<uint8_t> active(static_cast<size_t>(width) * height, 1);

    std::unique_ptr<Integrator> own;
    if (!options.integrator) own = makeIntegrator(scene, {maxSpp});
    RenderOptions o = options;
    o.integrator = options.integrator ? options.integrator : own.get();
    o.spp = maxSpp;
    o.keepSums = false;
    o.film = nullptr;
    o.accumulate = &sums;
    o.progressivePositions = true;

    RenderResult result;
    // Within a time budget the minimum is taken in rounds too, from one sample up, each cut to
    // the time left, so that a slow machine or a heavy model stops near its budget however
    // long the minimum would take; without one it is a single round (a reproducible image).
    const bool budget = adaptive.seconds > 0;
    int done = 0, roundSpp = budget ? 1 : minSpp;
    size_t activeCount = active.size();
    double pixelSampleSeconds = 0;  // per sample of one pixel, measured
    for (int round = 0;; ++round) {
        const bool everyPixel = done < minSpp;  // the minimum, which every pixel takes
        o.sampleBegin = done;
        o.sampleEnd = done + roundSpp;
        o.active = everyPixel ? nullptr : &active;
        const double before = elapsed();
        if (options.onProgress)
            o.onProgress = [&](const RenderProgress& p) {
                options.onProgress(withinJob(p, before, (done + roundSpp * p.fraction()) / maxSpp,
                                             adaptive.seconds));
            };
        RenderResult r = render(scene, o);
        result.rays += r.rays;
        result.tilesDone = r.tilesDone;
        result.tilesTotal = r.tilesTotal;
        if (!r.complete) {
            if (round == 0)  // later rounds leave every pixel at least one sample
                result.complete = false;
            else
                result.stoppedEarly = true;
            break;
        }
        result.passes = round + 1;
        const double seconds = elapsed() - before;
        if (activeCount > 0)
            pixelSampleSeconds = seconds / (static_cast<double>(activeCount) * roundSpp);
        done += roundSpp;

        // Which pixels go on: those above the threshold, below the cap, in the part rendered
        // (while the minimum is taken, all those rendered).
        activeCount = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                uint8_t& a = active[static_cast<size_t>(y) * width + x];
                if (!a) continue;
                const double n = sums.weight(x, y);
                a = n > 0 && done < maxSpp &&
                    (done < minSpp ||
                     !(pixelError(sums.sum(x, y).value(), sums.passes(x, y).squares, n) <
                       adaptive.threshold));
                activeCount += a;
            }
        if (activeCount == 0 || done >= maxSpp) break;
        // The next round: as many samples as all before, up to the minimum first, then at most
        // kMaxRoundSpp, cut to the cap and to the time left at the rate so far.
        int next = done < minSpp ? std::min(done, minSpp - done)
                                 : std::min({done, kMaxRoundSpp, maxSpp - done});
        if (budget) {
            const double left = adaptive.seconds - elapsed();
            const double fit =
                std::floor(left / (pixelSampleSeconds * static_cast<double>(activeCount)));
            if (fit < next) next = fit < 1 ? 0 : static_cast<int>(fit);
        }
        if (next < 1) break;
        roundSpp = next;
    }

    // The result: each pixel the mean of its own samples.
    result.film = sums.resolve();
    if (options.aovs) result.aovs = sums.resolvePasses();
    int most = 0;
    double total = 0, stopped = 0, rendered = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double n = sums.weight(x, y);
            if (!(n > 0)) continue;
            rendered += 1;
            total += n;
            most = std::max(most, static_cast<int>(n));
            stopped += pixelError(sums.sum(x, y).value(), sums.passes(x, y).squares, n) <
                       adaptive.threshold;
        }
    if (options.keepSums) {
        if (!options.aovs) sums.dropPasses();  // kept for the error alone
        result.sums = std::move(sums);
    }
    result.samplesPerPixel = most;
    result.meanSamplesPerPixel = rendered > 0 ? total / rendered : 0;
    result.converged = rendered > 0 ? stopped / rendered : 0;
    result.seconds = elapsed();
    if (options.onProgress && result.complete) {
        RenderProgress end{result.tilesTotal, result.tilesTotal, result.seconds, 1.0};
        options.onProgress(end);
    }
    return result;
}

}  // namespace glint
