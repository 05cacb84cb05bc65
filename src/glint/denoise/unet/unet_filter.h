#pragma once
/// Denoising with Open Image Denoise's U-Net (unet.h): what goes in and comes out of the network
/// as OIDN's own filter has it for HDR colour with albedo and normal ("RT", hdr), from the
/// published description of OIDN 2 and its sources' constants:
///  - the colour is scaled by an exposure chosen from the image (key 0.18 over the geometric
///    mean of the luminance of blocks of at most 16 x 16 pixels, blocks darker than 1e-8 left
///    out), clamped below at 0 and mapped by the perceptual-uniform transfer function "PU" (a
///    fit of the PU2 curve, Aydin et al. 2008), normalised so that 65504 maps to 1;
///  - the albedo is clamped to [0, 1]; the normal to [-1, 1] and mapped to [0, 1];
///  - the image is padded with zeros to a multiple of 16 on each side;
///  - the output is clamped below at 0 in the network's space, mapped back through the
///    transfer function's inverse and divided by the exposure.

#include <array>
#include <vector>

#include "glint/core/parallel.h"
#include "glint/denoise/unet/unet.h"
#include "glint/math/vec3.h"

namespace glint {

/// What a network denoises, as OIDN's filters have it: HDR colour (guided by the albedo and
/// normal if it reads them), or an albedo or a normal pass alone (to clean the passes that then
/// guide a network trained on clean ones: OIDN's "cleanAux"). An albedo goes in and comes out
/// clamped to [0, 1]; a normal is clamped to [-1, 1] and mapped to [0, 1] for the network.
enum class UNetRole { HdrColor, Albedo, Normal };

/// The images the network reads, each width * height pixels in rows, row 0 at the top: `color`
/// is the image to denoise (colour, or the albedo or normal pass for those roles). `albedo` and
/// `normal` guide colour for networks that read them (9 input channels: both; 6: albedo only).
struct UNetImages {
    int width = 0, height = 0;
    const Vec3* color = nullptr;
    const Vec3* albedo = nullptr;
    const Vec3* normal = nullptr;
    UNetRole role = UNetRole::HdrColor;
};

/// OIDN's exposure for HDR colour `color` (width * height pixels): 0.18 over the geometric mean
/// of the blocks' luminance; 1 for an image with no block brighter than 1e-8.
float autoexposure(const Vec3* color, int width, int height);

/// OIDN's PU transfer function, normalised: forward maps radiance 0 to 65504 to [0, 1], inverse
/// maps back.
float puForward(float radiance);
float puInverse(float value);

/// The network's input planes for `images` at `exposure` (colour; 1 for the other roles), padded
/// to multiples of 16.
FeatureMap unetInput(const UNet& net, const UNetImages& images, float exposure);

/// How unetDenoise() runs (its result never depends on these, but for the kernels' rounding).
struct UNetOptions {
    /// The kernels; Reference: the oracle, on the whole image at once.
    unet::KernelIsa isa = unet::bestKernelIsa();
    /// The most memory the network's maps may hold (UNet::bytesPerPixel()): a larger image is
    /// denoised in tiles, overlapping by the network's receptive radius so that each tile's
    /// output is the whole image's.
    double maxMemoryBytes = 1024.0 * 1024 * 1024;
    /// Tiles of this size (a multiple of 16 more than twice the overlap); 0: the largest
    /// within maxMemoryBytes.
    int tileSize = 0;
    /// With this, each layer's time in each tile is appended to it.
    std::vector<UNetLayerTime>* times = nullptr;
};

/// The tiles unetDenoise() cuts an image of `width` x `height` into for `net` and `options`,
/// as (x, y, size x, size y) windows of the image padded to multiples of 16.
std::vector<std::array<int, 4>> unetTiles(const UNet& net, int width, int height,
                                          const UNetOptions& options);

struct UNetResult {
    std::vector<Vec3> pixels;  ///< width * height
    /// Pixels with a value that was not finite (NaN, infinity) in an image the network read: each
    /// such value was taken as 0.
    size_t nonFinite = 0;
};

/// Denoises `images.color` with `net` (OIDN's weights for the role).
UNetResult unetDenoise(const UNet& net, const UNetImages& images, ThreadPool& pool,
                       const UNetOptions& options = {});

}  // namespace glint
