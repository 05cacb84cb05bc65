#pragma once
/// Rendering to a time budget (`--time SECONDS`): the image is rendered in passes over every
/// pixel, each with its own samples, until the budget is spent, and the passes are averaged,
/// each weighted by its samples. The first pass has 4 samples per pixel; each next one
/// doubles, up to 64, and is cut to what the time left allows at the rate measured so far, so
/// the render ends close to the budget and never starts a pass it cannot finish. A pass is
/// stratified and seeded on its own (pass k > 0 with a seed derived from the seed and k), so the
/// average converges as one render of as many samples would. The image depends on how many
/// passes fitted, so on the machine: for reproducible images, give `--spp` alone.

#include "glint/render/renderer.h"

namespace glint {

/// How long a render to a time budget may take.
struct TimeBudget {
    double seconds = 1;  ///< The budget, > 0: passes that would end after it are not started.
    /// At most this many samples per pixel in all (0: no limit but the time); the last pass is
    /// cut to end there.
    int maxSpp = 0;
};

/// Samples per pixel of the first pass, and the most a later pass takes.
inline constexpr int kFirstPassSpp = 4, kMaxPassSpp = 64;

/// Progress `p` of one render within a longer job (the passes here, adaptive.h's rounds) whose
/// render began `before` seconds into the job: its seconds counted from the job's start, and
/// RenderProgress::overall the larger of `samplesShare` (of the job's samples) and the time
/// over `budgetSeconds` (0: no budget), in [0, 1].
RenderProgress withinJob(const RenderProgress& p, double before, double samplesShare,
                         double budgetSeconds);

/// The seed of pass `pass` of a render seeded `seed`: `seed` itself for pass 0.
uint64_t passSeed(uint64_t seed, int pass);

/// Renders `scene` as render() does (options.spp is ignored), in passes until `budget` is
/// spent. Progress reports carry RenderProgress::overall: the larger of the time spent over the
/// budget and the samples done over budget.maxSpp. When cancelled during the first pass, the
/// result is that pass's partial image (complete false); after that, the passes finished
/// (stoppedEarly true). Throws as render() does.
RenderResult renderForTime(const Scene& scene, const RenderOptions& options,
                           const TimeBudget& budget);

}  // namespace glint
