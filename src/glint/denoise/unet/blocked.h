#pragma once
/// The layout the U-Net's fast kernels run on (unet.h runs them; the portable planes of
/// FeatureMap stay as the oracle). Channels go in blocks of 8: a block is a grid of pixels, each
/// pixel its 8 channels side by side, so that one 8-wide vector holds a pixel's block. Every
/// block's grid has a border of one zero pixel all round, so a 3x3 convolution reads its
/// neighbours with no test at the image's edges. A map of C channels has ceil(C / 8) blocks,
/// the channels past C zero.
///
/// A convolution reads one or more maps (sources) as if their channels were stacked (the
/// decoder's joins cost nothing), each source either at the convolution's size or at half of it,
/// read as if upsampled (nearest neighbour: the decoder's upsampling costs nothing either). It
/// writes each output row, ReLU applied, or with `pool`, each 2x2 block's largest value (the
/// encoder's pooling, fused).
///
/// Every kernel sums each output value in the same order (bias, then input blocks in order,
/// then the nine taps row by row, then the block's eight channels), whichever rows or blocks a
/// task takes: the result does not depend on how the work is split between threads. The AVX2
/// kernels fuse each multiply-add; the portable and SIMD128 ones round twice.

#include <cstddef>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

struct Conv3x3;

namespace unet {

/// Channels per block.
constexpr int kBlock = 8;

/// Floats on 64-byte boundaries, zero at first unless asked not to be; moved, never copied.
class AlignedFloats {
  public:
    AlignedFloats() = default;
    explicit AlignedFloats(size_t count, bool zeroed = true);
    float* data() { return data_.get(); }
    const float* data() const { return data_.get(); }
    size_t size() const { return size_; }

  private:
    struct Free {
        void operator()(float* p) const;
    };
    std::unique_ptr<float[], Free> data_;
    size_t size_ = 0;
};

/// An image of `channels` channels in blocks of kBlock, each with its zero border.
struct BlockedMap {
    int channels = 0, blocks = 0, height = 0, width = 0;
    AlignedFloats values;

    BlockedMap() = default;
    /// All zero.
    BlockedMap(int channels, int height, int width);
    /// In `storage` (at least floatsFor() floats, whatever they hold): the border set to zero,
    /// the rest left for its writer, which must write every pixel of every block.
    BlockedMap(int channels, int height, int width, AlignedFloats storage);
    static size_t floatsFor(int channels, int height, int width) {
        return static_cast<size_t>((channels + kBlock - 1) / kBlock) * (height + 2) * (width + 2) *
               kBlock;
    }
    /// Floats from one row of a block to the next, and from one block to the next.
    size_t rowStride() const { return static_cast<size_t>(width + 2) * kBlock; }
    size_t blockStride() const { return static_cast<size_t>(height + 2) * rowStride(); }
    /// Pixel (x, y) of block `b`: x from -1 to width, y from -1 to height (the border).
    float* at(int b, int y, int x) {
        return values.data() + b * blockStride() + (y + 1) * rowStride() + (x + 1) * kBlock;
    }
    const float* at(int b, int y, int x) const {
        return values.data() + b * blockStride() + (y + 1) * rowStride() + (x + 1) * kBlock;
    }
};

/// Storage for maps, kept when a map is given back so that the next map takes it rather than
/// fresh memory (which the system zeroes page by page: a third of a large image's time). Any
/// thread may take and give.
class MapPool {
  public:
    /// A map whose storage is the smallest free one large enough, or new.
    BlockedMap take(int channels, int height, int width);
    void give(BlockedMap map);
    /// The most bytes that maps taken and not given back have held at once.
    size_t peakBytes() const { return peak_ * sizeof(float); }

  private:
    std::mutex lock_;
    std::vector<AlignedFloats> free_;
    size_t held_ = 0, peak_ = 0;  // floats in maps taken and not given back
};

/// A convolution's weights as the kernels read them. Its input channels are those of its
/// sources stacked, each source's padded to whole blocks; its output blocks go in pairs (a last
/// odd one alone). For each pair, for each input block, tap (row by row) and channel of the
/// block: the weights of the pair's 16 outputs (8 for a block alone).
struct PackedConv {
    std::string name;
    int inChannels = 0, inBlocks = 0, outBlocks = 0, outChannels = 0;
    AlignedFloats weights, bias;  // bias: outBlocks * kBlock

    /// Floats per (input block, tap, channel) row of the pair that output block `b` is in.
    int pairWidth(int b) const { return (b / 2 * 2 + 1 < outBlocks ? 2 : 1) * kBlock; }
    /// The weights of output block `b`'s pair.
    const float* pairWeights(int b) const {
        return weights.data() + static_cast<size_t>(b / 2) * 2 * kBlock * inBlocks * 9 * kBlock;
    }
    float* pairWeights(int b) { return const_cast<float*>(std::as_const(*this).pairWeights(b)); }
};

/// `conv` packed for sources of `sourceChannels` channels (their sum is conv.in).
PackedConv packConv(const Conv3x3& conv, std::span<const int> sourceChannels);

/// A map a convolution reads, at its size or (upsampled) at half of it. A map of its size may
/// hold a band of its rows: row y is the map's row y - firstRow (rows past the band are not
/// read, but for the image's edges, which the map's border stands for).
struct ConvSource {
    const BlockedMap* map = nullptr;
    bool upsampled = false;
    int firstRow = 0;
};

/// One task of a convolution: its output rows [y0, y1) (of its own size, height x width) for
/// output blocks [block, block + blocks) (block even, blocks at most kMaxTaskBlocks), written
/// into `out` as they are or (pool: y0 and y1 even) pooled, as out's rows y0 / 2 to y1 / 2.
/// `scratch`, with pool: 2 * width * blocks * kBlock floats. `out` may hold a band of rows,
/// from outFirstRow (of its own: pooled rows if pooled).
constexpr int kMaxTaskBlocks = 4;
struct ConvRows {
    const PackedConv* conv = nullptr;
    std::span<const ConvSource> sources;
    int height = 0, width = 0;
    int block = 0, blocks = 0;
    int y0 = 0, y1 = 0;
    bool pool = false;
    BlockedMap* out = nullptr;
    int outFirstRow = 0;
    float* scratch = nullptr;
};

/// The kernels' instruction sets; Reference: not these kernels at all but the planar oracle
/// (UNet::runReference()).
enum class KernelIsa { Reference, Portable, Avx2, Avx512, Simd128 };

/// The best this machine and build have.
KernelIsa bestKernelIsa();
std::string_view kernelIsaName(KernelIsa isa);
/// The instruction set of that name; throws std::invalid_argument for another.
KernelIsa kernelIsaNamed(std::string_view name);
/// Whether this build and machine run `isa`.
bool runs(KernelIsa isa);

/// Runs a task with the kernels of `isa` (which must run here).
void convolveRows(KernelIsa isa, const ConvRows& task);
/// The output blocks a task of `isa` best takes (two vectors' worth).
int taskBlocks(KernelIsa isa);

/// The kernels of each instruction set (conv_*.cpp).
namespace portable {
void convolveRows(const ConvRows& task);
}
namespace avx2 {
void convolveRows(const ConvRows& task);
}
namespace avx512 {
void convolveRows(const ConvRows& task);
}
namespace simd128 {
void convolveRows(const ConvRows& task);
}

}  // namespace unet
}  // namespace glint
