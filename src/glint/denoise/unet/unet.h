#pragma once
/// Open Image Denoise's U-Net (Intel, Apache-2.0 weights; docs/denoiser-method.md), run by
/// Glint's own inference: the network's layers are read from an archive of its published
/// weights (tza.h), its shape from their names and sizes. Every layer is a 3x3 convolution with
/// a bias and a ReLU; the encoder halves the image four times by 2x2 max pooling, the decoder
/// doubles it again by nearest-neighbour upsampling, each time joined (channels stacked, the
/// upsampled ones first) with the encoder's image of that size, the last time with the input:
///
///     input -> enc1 -> pool1 -> enc2 -> pool2 -> enc3 -> pool3 -> enc4 -> pool4 -> bottom -> up
///     [up, pool3] -> dec4 -> up   [up, pool2] -> dec3 -> up   [up, pool1] -> dec2 -> up
///     [up, input] -> dec1 -> output
///
/// OIDN's "fast" and "balanced" weights name their layers enc_conv0, enc_conv1 (level 1),
/// enc_conv2 to 4, enc_conv5a/b (bottom), dec_conv4a/b to dec_conv2a/b and dec_conv1a, 1b and
/// dec_conv0; its "high" weights have two layers per encoder level (enc_convNa/b) and end in
/// dec_conv1c. The input and output sizes must be multiples of 16 (kAlignment).
///
/// run() runs the fast kernels (blocked.h: channels in blocks of 8, joins, upsampling and
/// pooling fused into the convolutions, AVX2 where the machine has it). runReference() is the
/// oracle they are checked against: plain loops over channel-major planes, in float, each output
/// channel computed on its own. Neither result depends on the threads.

#include <array>
#include <string>
#include <vector>

#include "glint/core/parallel.h"
#include "glint/denoise/unet/blocked.h"
#include "glint/denoise/unet/tza.h"

namespace glint {

/// An image of `channels` planes, each height x width floats, row by row, plane after plane.
struct FeatureMap {
    int channels = 0, height = 0, width = 0;
    std::vector<float> values;

    FeatureMap() = default;
    FeatureMap(int c, int h, int w)
        : channels(c), height(h), width(w), values(static_cast<size_t>(c) * h * w, 0.0f) {}
    float* plane(int c) { return values.data() + static_cast<size_t>(c) * height * width; }
    const float* plane(int c) const {
        return values.data() + static_cast<size_t>(c) * height * width;
    }
    float& at(int c, int y, int x) { return plane(c)[static_cast<size_t>(y) * width + x]; }
    float at(int c, int y, int x) const { return plane(c)[static_cast<size_t>(y) * width + x]; }
};

/// A 3x3 convolution with a bias: weights out x in x 3 x 3 (OIDN's "oihw"), bias out.
struct Conv3x3 {
    std::string name;
    int in = 0, out = 0;
    std::vector<float> weights, bias;
};

/// How long one layer took in a run (UNet::run's `times`).
struct UNetLayerTime {
    std::string name;
    int width = 0, height = 0;
    double seconds = 0, multiplyAdds = 0;
};

class UNet {
  public:
    /// Pooled four times: inputs are padded to a multiple of this on each side.
    static constexpr int kAlignment = 16;

    /// The network whose weights `tensors` are (OIDN's base, small or large U-Net). Throws
    /// std::runtime_error naming a missing layer or one whose size does not fit its input.
    static UNet fromTensors(const TzaTensors& tensors);

    int inputChannels() const { return encoder_[0].front().in; }
    int outputChannels() const { return decoder_[0].back().out; }
    /// Weights in all.
    size_t parameters() const;
    /// Multiply-adds per pixel of the input.
    double multiplyAddsPerPixel() const;

    /// The network's output for `input` (inputChannels() planes, sides multiples of
    /// kAlignment): outputChannels() planes of the same size, by the kernels of `isa` (which must
    /// run here).
    /// With `times`, each layer's time is appended to it (the blocked kernels only).
    FeatureMap run(const FeatureMap& input, ThreadPool& pool,
                   unet::KernelIsa isa = unet::bestKernelIsa(),
                   std::vector<UNetLayerTime>* times = nullptr) const;
    /// The same by the portable oracle (equal to rounding).
    FeatureMap runReference(const FeatureMap& input, ThreadPool& pool) const;
    /// The network on `input` (inputChannels() channels, sides multiples of kAlignment) by the
    /// blocked kernels of `isa`, its maps taken from `maps` and all but the result given back.
    unet::BlockedMap run(const unet::BlockedMap& input, unet::MapPool& maps, ThreadPool& pool,
                         unet::KernelIsa isa = unet::bestKernelIsa(),
                         std::vector<UNetLayerTime>* times = nullptr) const;

    /// How far (in pixels, either way) an output pixel's value reaches into the input, at
    /// most: a tile's output is the whole image's where it is this far from the tile's edges
    /// (those inside the image).
    int receptiveRadius() const;
    /// The bytes run() holds per pixel of its input, at most (its maps' padding aside).
    double bytesPerPixel() const;

  private:
    /// Encoder levels 1 to 4 (each followed by pooling), the bottom (followed by upsampling),
    /// decoder levels 1 to 4 (each after the join; all but level 1 followed by upsampling).
    std::array<std::vector<Conv3x3>, 4> encoder_, decoder_;
    std::vector<Conv3x3> bottom_;
    /// The same layers packed for the kernels (the decoder's first layers for two sources).
    std::array<std::vector<unet::PackedConv>, 4> packedEncoder_, packedDecoder_;
    std::vector<unet::PackedConv> packedBottom_;
};

/// `conv` on `in`, then ReLU: the portable kernel (unet.cpp).
FeatureMap convolveRelu(const Conv3x3& conv, const FeatureMap& in, ThreadPool& pool);
/// Each 2x2 block's largest value: half the size (sides must be even).
FeatureMap maxPool2x2(const FeatureMap& in);
/// Each value four times: twice the size.
FeatureMap upsample2x(const FeatureMap& in);
/// `a`'s planes, then `b`'s (of the same size).
FeatureMap concatenate(const FeatureMap& a, const FeatureMap& b);

}  // namespace glint
