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
    /// The first pass: guided by the noisy colour itself.
    NlMeansParams first{.radius = 8,
                        .patch = 1,
                        .k = 0.55f,
                        .alpha = 1.0f,
                        .normalWeight = 20.0f,
                        .albedoWeight = 5.0f,
                        .depthWeight = 100.0f,
                        .firstOrder = true,
                        .ridge = 0.01f,
                        .innerRadius = 3};
    /// With first.innerRadius > 0, each pixel takes the inner window's mean where Stein's
    /// unbiased risk estimate, summed over a box of this radius, says it is the better one
    /// (selectBySure in denoise.cpp) ...
    int sureRadius = 4;
    /// ... the variance in the estimate being this times the smoothed variance.
    float sureVarianceScale = 2.0f;
    /// A second pass, guided by the first's result (none if its radius is 0): it measured worse
    /// than one pass on the synthetic scenes (bench/denoise_eval), so it is off.
    NlMeansParams second{.radius = 0,
                         .patch = 1,
                         .k = 0.45f,
                         .alpha = 1.0f,
                         .normalWeight = 20.0f,
                         .albedoWeight = 20.0f,
                         .depthWeight = 400.0f};
    /// The variance the second pass assumes of its guide: this times the first pass's own.
    float secondGuideVarianceScale = 1.0f;
};

/// denoise() with explicit parameters.
std::vector<Vec3> denoiseTuned(const DenoiseInput& in, const DenoiseOptions& options,
                               const DenoiseTuning& tuning);

}  // namespace glint::denoise_detail
