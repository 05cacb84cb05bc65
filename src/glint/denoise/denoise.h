#pragma once
/// Glint's image-space denoiser: a noisy Monte Carlo image and its feature buffers (albedo,
/// normal, depth, the variance of each pixel's mean) in, a denoised image out. It knows images,
/// not scenes: the renderer writes the buffers, this stage reads them (docs/denoiser-method.md).
///
/// The method: colour is divided by albedo (the "demodulated irradiance", so that texture
/// detail is never blurred) and filtered by joint non-local means, each neighbour weighted by
/// its patch's colour distance normalised by the two pixels' variances and by its distance in
/// normal, depth and albedo. The result is multiplied by albedo again.

#include <vector>

#include "glint/core/parallel.h"
#include "glint/math/vec3.h"

namespace glint {

/// The buffers to denoise, each width * height pixels in rows, row 0 at the top. Not owned:
/// they must outlive the call. Only `color` is required.
struct DenoiseInput {
    int width = 0, height = 0;
    /// Linear radiance per pixel.
    const Vec3* color = nullptr;
    /// The first non-specular surface's albedo, in [0, 1]; 0 where no surface was hit (sky).
    const Vec3* albedo = nullptr;
    /// That surface's world-space shading normal, averaged over the pixel's samples (length at
    /// most 1); 0 where no surface was hit.
    const Vec3* normal = nullptr;
    /// Distance from the camera to the first hit; 0 where no surface was hit.
    const double* depth = nullptr;
    /// Per channel, the variance of each pixel's mean (the sample variance over the sample
    /// count). Null: estimated from the image itself, from differences between neighbours.
    const Vec3* variance = nullptr;
    /// Per channel, the variance of each pixel's albedo (the same estimate). Where it is large
    /// (an alpha-blended or glass surface, whose samples see different surfaces at random) the
    /// albedo is filtered before it multiplies the result. Null: the albedo is taken as it is.
    const Vec3* albedoVariance = nullptr;
};

/// How to run the denoiser (its result never depends on these).
struct DenoiseOptions {
    /// The threads to run on; null: a pool of `threads` threads made for the call.
    ThreadPool* pool = nullptr;
    /// With no pool: the number of threads (0: hardwareThreads()).
    int threads = 0;
};

/// Returns the denoised colour, width * height pixels in the layout of `in.color`. Deterministic:
/// bit-identical for any pool or thread count. Non-finite input values are treated as 0.
/// Throws std::invalid_argument on a negative size or a missing colour buffer.
std::vector<Vec3> denoise(const DenoiseInput& in, const DenoiseOptions& options = {});

}  // namespace glint
