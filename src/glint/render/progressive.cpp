#include "glint/render/progressive.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "glint/math/rng.h"

namespace glint {

RenderProgress withinJob(const RenderProgress& p, double before, double samplesShare,
                         double budgetSeconds) {
    RenderProgress q = p;
    q.seconds = before + p.seconds;
    const double share =
        budgetSeconds > 0 ? std::max(samplesShare, q.seconds / budgetSeconds) : samplesShare;
    q.overall = std::clamp(share, 0.0, 1.0);
    return q;
}

uint64_t passSeed(uint64_t seed, int pass) {
    if (pass == 0) return seed;
    return mixBits(seed ^ mixBits(0xd1b54a32d192ed03ULL * static_cast<uint64_t>(pass)));
}

RenderResult renderForTime(const Scene& scene, const RenderOptions& options,
                           const TimeBudget& budget) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const int maxSpp = budget.maxSpp > 0 ? budget.maxSpp : 1 << 30;

    RenderResult result;
    Film sum(scene.width, scene.height);
    FilmSums passSums;  // with passes: every pass's sums, for them (beauty stays as below)
    if (options.aovs) {
        passSums = FilmSums(scene.width, scene.height);
        passSums.keepPasses();
    }
    int spp = 0, passSpp = std::min(kFirstPassSpp, maxSpp);
    for (int pass = 0;; ++pass) {
        RenderOptions o = options;
        o.spp = passSpp;
        o.seed = passSeed(options.seed, pass);
        if (options.aovs) o.keepSums = true;
        const double before = elapsed();
        if (options.onProgress)
            o.onProgress = [&](const RenderProgress& p) {
                options.onProgress(
                    withinJob(p, before, (spp + passSpp * p.fraction()) / maxSpp, budget.seconds));
            };
        RenderResult r = render(scene, o);
        result.rays += r.rays;
        if (!r.complete) {
            if (pass == 0) {  // nothing finished: the partial pass, as render() leaves it
                r.seconds = elapsed();
                return r;
            }
            result.stoppedEarly = true;
            break;
        }
        if (options.aovs) passSums.add(r.sums);
        // Sum the pass, weighted by its samples.
        for (int y = 0; y < scene.height; ++y)
            for (int x = 0; x < scene.width; ++x) sum.at(x, y) += r.film.at(x, y) * double(passSpp);
        spp += passSpp;
        result.passes = pass + 1;
        result.tilesDone = r.tilesDone;
        result.tilesTotal = r.tilesTotal;
        if (spp >= maxSpp) break;
        // The next pass: twice this one, up to kMaxPassSpp, cut to the samples left and to the
        // time left at the rate so far. None when not even two samples fit (one sample per
        // pixel is its centre: only as the last one the sample limit asks for).
        const double now = elapsed(), perSample = now / spp;
        const double fit = std::floor((budget.seconds - now) / perSample);
        const int left = maxSpp - spp;
        int next = std::min({2 * passSpp, kMaxPassSpp, left});
        if (fit < next) next = fit < 1 ? 0 : static_cast<int>(fit);
        if (next < 1 || (next == 1 && left > 1)) break;
        passSpp = next;
    }
    const double weight = 1.0 / spp;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) sum.at(x, y) = sum.at(x, y) * weight;
    result.film = std::move(sum);
    if (options.aovs) result.aovs = passSums.resolvePasses();
    result.samplesPerPixel = spp;
    result.seconds = elapsed();
    result.complete = true;
    if (options.onProgress) {
        RenderProgress done{result.tilesTotal, result.tilesTotal, result.seconds, 1.0};
        options.onProgress(done);
    }
    return result;
}

}  // namespace glint
