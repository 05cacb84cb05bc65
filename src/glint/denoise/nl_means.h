#pragma once
/// Joint non-local means (Rousselle, Knaus and Zwicker 2012 and 2013): every pixel p becomes the
/// weighted mean of the pixels q in a square window around it, each weighted by
///   exp(-(max(0, d_colour(p, q)) + d_features(p, q)))
/// where d_colour is the mean, over a small patch and the three channels, of the
/// variance-cancelled, variance-normalised squared difference of a guide image
///   ((g_p - g_q)^2 - alpha (v_p + min(v_p, v_q))) / (eps + k^2 (v_p + v_q)),
/// and d_features the squared differences of normal, albedo and depth (the latter from the
/// plane through p: the depth p's gradient predicts at q), each times its weight. Internal to
/// denoise/.

#include <array>

#include "glint/core/parallel.h"
#include "glint/denoise/plane.h"

namespace glint::denoise_detail {

/// The buffers that guide the weights. Colour planes need a border of at least `patch` pixels;
/// a null feature plane is left out of the distance.
struct NlMeansGuide {
    std::array<const Plane*, 3> color{};     // the guide colour g
    std::array<const Plane*, 3> variance{};  // the variance v of g
    std::array<const Plane*, 3> normal{};
    std::array<const Plane*, 3> albedo{};
    const Plane* depth = nullptr;
    const Plane* depthDx = nullptr;  // the depth's one-sided gradient (the smaller one), per pixel
    const Plane* depthDy = nullptr;
};

/// The filter's parameters.
struct NlMeansParams {
    int radius = 8;             // the window: (2 radius + 1)^2 pixels
    int patch = 1;              // the patch: (2 patch + 1)^2 pixels
    float k = 0.45f;            // colour sensitivity: larger blurs more
    float alpha = 1.0f;         // variance cancellation
    float normalWeight = 0.0f;  // times |n_p - n_q|^2
    float albedoWeight = 0.0f;  // times |a_p - a_q|^2
    float depthWeight = 0.0f;   // times (depth residual / depth_p)^2
    /// First order: each result is the value at p of a weighted least-squares fit of the values
    /// in the window as a linear function of the position (a plane), not their weighted mean,
    /// so that a gradient is not flattened and a window that meets an edge on one side is not
    /// pulled towards its other side's mean.
    bool firstOrder = false;
    float ridge = 0.01f;  // the fit's slopes' ridge, times the weights' sum
    /// A pixel whose window (and its patches) holds no pixel of any guide variance keeps its
    /// value: nothing there is noisy, and a difference rejects any neighbour anyway; tiles of
    /// such pixels are not filtered at all. (The albedo's filter: most of a model's image has
    /// an exact albedo.)
    bool keepExact = false;
};

/// Where nlMeans writes; only `value` is required.
struct NlMeansOutputs {
    std::array<Plane*, 3> value{};
    /// The variance of each result from the variances of the values, as if they were
    /// independent: the weighted mean's, for a first-order fit times the ratio of the fit's
    /// leverage (the result's derivative by its own pixel's value, the weights held fixed) to
    /// the mean's, exact for equal weights and variances.
    std::array<Plane*, 3> variance{};
};

/// Filters `values` (three unpadded-or-padded planes of the guide's size) into `out`, whose
/// variance output needs `valueVariance`, the variances of the values. Deterministic for any
/// pool.
void nlMeans(const NlMeansGuide& guide, const std::array<const Plane*, 3>& values,
             const NlMeansParams& params, const NlMeansOutputs& out,
             const std::array<const Plane*, 3>* valueVariance, ThreadPool& pool);

}  // namespace glint::denoise_detail
