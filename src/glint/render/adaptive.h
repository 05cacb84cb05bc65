#pragma once
/// Adaptive sampling (`--noise-threshold T`, Blender Cycles' name and meaning): each pixel takes
/// samples until its estimated error falls below T, at least `minSpp` of them and at most
/// `maxSpp` (`--spp`), optionally within a time budget (`--time`).
///
/// The image is rendered in rounds over the pixels still sampling. Round 0 takes samples
/// [0, minSpp) of every pixel (within a time budget: rounds of 1, 1, 2, 4, ... samples of every
/// pixel up to minSpp, each cut to the time left, so that a heavy scene on a busy machine
/// still stops near its budget, with at least one sample in every pixel); each later round the next
/// samples of the pixels not yet stopped, twice as many as all rounds before it, at most
/// kMaxRoundSpp, cut to the cap. After each round a pixel stops when its error is below T. A
/// pixel's samples are those of one render of its sample count: the same indices, at sub-pixel
/// positions spread in every prefix (sampler.h, progressive positions), so wherever it stops its
/// samples cover it evenly.
///
/// The error is Cycles' form of a pixel's relative error, with the standard error of each
/// channel's mean (from the pixel's own samples) for its noise:
///
///     error = (s_R + s_G + s_B) / (1e-4 + sqrt(R + G + B)),  s_c = sqrt(var(c) / n)
///
/// relative to the square root of the brightness, so dark pixels are held to less than bright
/// ones, as a viewer (and a display's gamma) sees them.
///
/// Each pixel's stop depends on its own samples only: without a time budget the image does not
/// depend on the threads, on how the frame is cut into pieces, or on the machine. With one, the
/// last rounds are cut to the time left at the rate measured, as `--time` alone does
/// (progressive.h), so the image then depends on the machine's speed.

#include <cstdint>

#include "glint/render/renderer.h"

namespace glint {

struct AdaptiveOptions {
    double threshold = 0.01;  ///< The error a pixel stops at, > 0.
    int minSpp = 0;      ///< Samples every pixel takes first; 0: kDefaultMinSpp (at most maxSpp).
    int maxSpp = 1024;   ///< The most a pixel takes.
    double seconds = 0;  ///< Time budget; 0: none (the image is then reproducible).
};

/// The default minimum: enough samples that a pixel's own variance is a fair estimate.
inline constexpr int kDefaultMinSpp = 16;
/// The most samples one round adds to a pixel.
inline constexpr int kMaxRoundSpp = 64;

/// The error above of a pixel whose `n` samples sum to `sum` with squares summing to `squares`;
/// infinite below two samples.
double pixelError(const Vec3& sum, const Vec3& squares, double n);

/// Renders `scene` as render() does, adaptively (options.spp, sampleBegin and sampleEnd are
/// ignored; crop and parts are honoured). RenderResult::samplesPerPixel is the most samples a
/// pixel took, meanSamplesPerPixel their mean, converged the share of pixels that stopped below
/// the threshold. Cancelled in round 0: that round's partial image (complete false); later: the
/// image of the samples taken (stoppedEarly). Throws as render() does.
RenderResult renderAdaptive(const Scene& scene, const RenderOptions& options,
                            const AdaptiveOptions& adaptive);

}  // namespace glint
