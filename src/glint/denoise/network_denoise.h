#pragma once
/// The network denoiser: Open Image Denoise's U-Net, run by Glint's own inference (unet/), with
/// OIDN's published weights (denoise-weights/README.md; unet/weights.h) chosen as OIDN chooses
/// them for the passes there are and the quality asked for (docs/denoiser-method.md):
///
///   quality    with albedo and normal                     albedo only       colour only
///   fast       rt_hdr_alb_nrm_small                       rt_hdr_alb_small  rt_hdr_small
///   balanced   rt_hdr_alb_nrm                             rt_hdr_alb        rt_hdr
///   high       rt_alb_large and rt_nrm_large clean the    rt_hdr_alb        rt_hdr
///              passes, then rt_hdr_calb_cnrm_large
///
/// (OIDN has no larger network for noisy passes or for fewer of them: high is balanced there.)

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "glint/core/parallel.h"
#include "glint/denoise/denoise.h"
#include "glint/math/vec3.h"

namespace glint {

class UNet;

enum class DenoiseQuality { Fast, Balanced, High };

/// "fast", "balanced", "high"; and back (throws std::invalid_argument for another name).
std::string_view denoiseQualityName(DenoiseQuality quality);
DenoiseQuality denoiseQualityNamed(std::string_view name);

/// The weights for `quality` and the passes there are: the colour's network, and the albedo's
/// and normal's (empty: the passes guide as they are).
struct NetworkChoice {
    std::string color, albedo, normal;
};
NetworkChoice networkChoice(DenoiseQuality quality, bool albedo, bool normal);

/// Whether the weights `choice` names are here (built in or registered).
bool networkWeightsHere(const NetworkChoice& choice);
/// Whether the weights of `quality` are here for every set of passes.
bool networkDenoiserAvailable(DenoiseQuality quality = DenoiseQuality::Balanced);

/// The network of the weights `name`, read and packed once per process (any thread). Throws
/// std::runtime_error if they are not here, saying how to get them.
std::shared_ptr<const UNet> denoiserNetwork(std::string_view name);

struct NetworkDenoised {
    std::vector<Vec3> color;
    /// Pixels with a value that was not finite in an image the networks read (taken as 0).
    size_t nonFinite = 0;
};

/// Denoises `in.color` guided by `in.albedo` and `in.normal` where given (the other buffers
/// are not read). Throws std::runtime_error if the weights are not here.
NetworkDenoised networkDenoise(const DenoiseInput& in, DenoiseQuality quality, ThreadPool& pool);

}  // namespace glint
