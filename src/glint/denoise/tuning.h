#pragma once
/// The denoiser's parameters, as measured (bench/denoise_eval.cpp sweeps them): denoise() uses
/// the defaults. Internal to denoise/ and its tools.

#include <vector>

#include "glint/denoise/denoise.h"
#include "glint/denoise/nl_means.h"

namespace glint::denoise_detail {

struct DenoiseTuning {
    /// The colour is divided by max(albedo, this) per channel, and multiplied back by the same:
    /// continuous in the albedo. 0.1 measured best over the five benchmark scenes (0.01 with a
    /// cut-off instead made the models' dark-albedo regions 10 to 40 times worse than raw).
    float albedoFloor = 0.1f;
    /// Radius of the box filter that smooths the variance buffer (it is noisy itself).
    int varianceRadius = 2;
    /// Without a variance buffer: the estimate from neighbour differences times this.
    float estimatedVarianceScale = 1.0f;
    /// A pixel whose own variance exceeds this times the smoothed one (an outlier: a firefly)
    /// keeps its own, which lets its neighbours take it in and spread its energy rather than
    /// leave a spot; 0: never. Only outliers: keeping every pixel's own variance would tie the
    /// weights to the noise and darken the image (a low sample has a low variance). 2 measured
    /// better than 4 on the real renders (room at 16 spp: 87x against 71x, its mean -0.5%
    /// against -1.5%; glass unchanged).
    float outlierVariance = 2.0f;
    /// The first pass, guided by the noisy colour itself: a small window, whose result only
    /// guides the second pass's weights. Measured on the five renders at 16 spp
    /// (docs/denoiser-method.md): one first-order pass of radius 8 gave glass 6.8x, room 82.7x,
    /// lamps 33.5x, helmet 3.6x, bottle 9.0x, its weights tied to the noise (room's mean -1.0%,
    /// -2.6% at 4 spp); these two passes give 7.4x, 68.8x, 31.1x, 3.8x, 13.3x, means within 0.2%
    /// (-1.4% on room at 4 spp), in the time of the old single zero-order pass of radius 8 (radius
    /// 3 and 6; a second radius of 7 gives glass 7.5x, room 77.4x, lamps 32.3x, bottle 13.6x,
    /// helmet the same, in 1.2 times the time, too near 1080p's 2 s).
    NlMeansParams first{.radius = 3,
                        .patch = 1,
                        .k = 0.8f,
                        .alpha = 1.0f,
                        .normalWeight = 20.0f,
                        .albedoWeight = 5.0f,
                        .depthWeight = 100.0f,
                        .firstOrder = true,
                        .ridge = 0.01f};
    /// The second pass (none if its radius is 0): the weights from the first's result, far less
    /// noisy than the colour, so they no longer pick the pixels whose noise is low (which darkened
    /// the image); the values again the noisy irradiance. First order (lamps 25.7x without).
    NlMeansParams second{.radius = 6,
                         .patch = 1,
                         .k = 1.0f,
                         .alpha = 1.0f,
                         .normalWeight = 10.0f,
                         .albedoWeight = 5.0f,
                         .depthWeight = 400.0f,
                         .firstOrder = true,
                         .ridge = 0.1f};
    /// The variance the second pass assumes of its guide: this times the first pass's own
    /// (its weighted mean's, times the ratio of the fit's leverage to the mean's). Smaller keeps
    /// more detail: 1 gave helmet 3.6x and room 79x at 16 spp, 0.8 3.8x and 74x, 0.5 3.9x and
    /// 60x.
    float secondGuideVarianceScale = 0.8f;
    /// ... but at least this times an outlier's own variance (outlierVariance), so that the
    /// second pass spreads a firefly's energy as the first does. Without it (0) the synthetic
    /// scene (fireflies of 100 times the mean) lost 0.75% of its mean and room measured 65.9x at
    /// 16 spp; with 0.03 0.62% and 68.5x, the rest the same (0.1: helmet 3.8x -> 3.7x).
    float secondOutlierVariance = 0.03f;
    /// The albedo's own filter (with an albedo variance; radius 0: none): non-local means over
    /// the albedo guided by itself and its variance, so that only the albedo's noise is averaged
    /// (a pixel whose samples all saw the same texel has no variance, and any difference to it
    /// rejects a neighbour). The filtered albedo multiplies the result back and guides the
    /// colour's weights; the colour is still divided by the pixel's own albedo, whose noise its
    /// samples share. k = 0.7 measured against 1 at 16 spp: glass 8.0x against 7.4x, helmet
    /// 3.9x against 3.7x (a larger k blurs texture whose pixels span texels: 2 gave glass 3.5x),
    /// the vase the same.
    NlMeansParams albedo{.radius = 3,
                         .patch = 1,
                         .k = 0.7f,
                         .alpha = 1.0f,
                         .normalWeight = 20.0f,
                         .albedoWeight = 0.0f,
                         .depthWeight = 100.0f,
                         .firstOrder = false,
                         .ridge = 0.01f,
                         .keepExact = true};
    /// (Its variance is used as it is: smoothing it by a 3x3 box measured the same or slightly
    /// worse, glass 7.9x against 8.0x; dividing the colour by the filtered albedo instead of the
    /// pixel's own, worse: the vase's error 0.0131 against 0.0111.)
};

/// denoise() with explicit parameters.
std::vector<Vec3> denoiseTuned(const DenoiseInput& in, const DenoiseOptions& options,
                               const DenoiseTuning& tuning);

}  // namespace glint::denoise_detail
