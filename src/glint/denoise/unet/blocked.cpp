#include "glint/denoise/unet/blocked.h"

#include <algorithm>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "glint/denoise/unet/unet.h"

namespace glint::unet {

AlignedFloats::AlignedFloats(size_t count, bool zeroed)
    : data_(static_cast<float*>(::operator new[](count * sizeof(float), std::align_val_t(64)))),
      size_(count) {
    if (zeroed) std::fill(data_.get(), data_.get() + count, 0.f);
}

void AlignedFloats::Free::operator()(float* p) const {
    ::operator delete[](p, std::align_val_t(64));
}

BlockedMap::BlockedMap(int c, int h, int w)
    : channels(c), blocks((c + kBlock - 1) / kBlock), height(h), width(w) {
    values = AlignedFloats(static_cast<size_t>(blocks) * blockStride());
}

BlockedMap::BlockedMap(int c, int h, int w, AlignedFloats storage)
    : channels(c), blocks((c + kBlock - 1) / kBlock), height(h), width(w) {
    if (storage.size() < floatsFor(c, h, w))
        throw std::invalid_argument("BlockedMap: storage too small");
    values = std::move(storage);
    for (int b = 0; b < blocks; ++b) {
        std::fill(at(b, -1, -1), at(b, -1, w + 1), 0.f);
        std::fill(at(b, h, -1), at(b, h, w + 1), 0.f);
        for (int y = 0; y < h; ++y) {
            std::fill(at(b, y, -1), at(b, y, 0), 0.f);
            std::fill(at(b, y, w), at(b, y, w + 1), 0.f);
        }
    }
}

BlockedMap MapPool::take(int channels, int height, int width) {
    const size_t n = BlockedMap::floatsFor(channels, height, width);
    std::unique_lock hold(lock_);
    auto best = free_.end();
    for (auto it = free_.begin(); it != free_.end(); ++it)
        if (it->size() >= n && (best == free_.end() || it->size() < best->size())) best = it;
    AlignedFloats storage;
    if (best != free_.end()) {
        storage = std::move(*best);
        free_.erase(best);
        held_ += storage.size();
    } else {
        held_ += n;
        hold.unlock();  // the system's pages are slow to come: let others go on meanwhile
        storage = AlignedFloats(n, /*zeroed=*/false);
        hold.lock();
    }
    peak_ = std::max(peak_, held_);
    hold.unlock();
    return BlockedMap(channels, height, width, std::move(storage));
}

void MapPool::give(BlockedMap map) {
    const std::lock_guard hold(lock_);
    held_ -= map.values.size();
    free_.push_back(std::move(map.values));
}

PackedConv packConv(const Conv3x3& conv, std::span<const int> sourceChannels) {
    PackedConv p;
    p.name = conv.name;
    p.inChannels = conv.in;
    // Input channel i's block and channel in it, the sources' channels each padded to blocks.
    std::vector<int> blockOf, laneOf;
    for (int channels : sourceChannels) {
        for (int c = 0; c < channels; ++c) {
            blockOf.push_back(p.inBlocks + c / kBlock);
            laneOf.push_back(c % kBlock);
        }
        p.inBlocks += (channels + kBlock - 1) / kBlock;
    }
    if (static_cast<int>(blockOf.size()) != conv.in)
        throw std::invalid_argument("packConv: layer '" + conv.name + "' takes " +
                                    std::to_string(conv.in) + " channels, its sources give " +
                                    std::to_string(blockOf.size()));
    p.outChannels = conv.out;
    p.outBlocks = (conv.out + kBlock - 1) / kBlock;
    const size_t pairs = static_cast<size_t>(p.outBlocks + 1) / 2;
    p.weights = AlignedFloats(pairs * 2 * kBlock * p.inBlocks * 9 * kBlock);
    p.bias = AlignedFloats(static_cast<size_t>(p.outBlocks) * kBlock);
    for (int o = 0; o < conv.out; ++o) {
        p.bias.data()[o] = conv.bias[static_cast<size_t>(o)];
        const int block = o / kBlock, width = p.pairWidth(block);
        float* pair = p.pairWeights(block);
        const int column = (block % 2) * kBlock + o % kBlock;
        for (int i = 0; i < conv.in; ++i)
            for (int tap = 0; tap < 9; ++tap) {
                const size_t row = (static_cast<size_t>(blockOf[i]) * 9 + tap) * kBlock + laneOf[i];
                pair[row * width + column] =
                    conv.weights[(static_cast<size_t>(o) * conv.in + i) * 9 + tap];
            }
    }
    return p;
}

bool runs(KernelIsa isa) {
    switch (isa) {
        case KernelIsa::Reference:
        case KernelIsa::Portable:
            return true;
        case KernelIsa::Avx2:
#if GLINT_HAVE_AVX2
            return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
            return false;
#endif
        case KernelIsa::Avx512:
#if GLINT_HAVE_AVX2
            return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
#else
            return false;
#endif
        case KernelIsa::Simd128:
            return GLINT_HAVE_SIMD128 != 0;
    }
    return false;
}

KernelIsa bestKernelIsa() {
    static const KernelIsa best = runs(KernelIsa::Avx512)    ? KernelIsa::Avx512
                                  : runs(KernelIsa::Avx2)    ? KernelIsa::Avx2
                                  : runs(KernelIsa::Simd128) ? KernelIsa::Simd128
                                                             : KernelIsa::Portable;
    return best;
}

std::string_view kernelIsaName(KernelIsa isa) {
    switch (isa) {
        case KernelIsa::Reference:
            return "reference";
        case KernelIsa::Portable:
            return "portable";
        case KernelIsa::Avx2:
            return "avx2";
        case KernelIsa::Avx512:
            return "avx512";
        case KernelIsa::Simd128:
            return "simd128";
    }
    return "?";
}

KernelIsa kernelIsaNamed(std::string_view name) {
    for (KernelIsa isa : {KernelIsa::Reference, KernelIsa::Portable, KernelIsa::Avx2,
                          KernelIsa::Avx512, KernelIsa::Simd128})
        if (kernelIsaName(isa) == name) return isa;
    throw std::invalid_argument("no kernels named '" + std::string(name) +
                                "' (reference, portable, avx2, avx512, simd128)");
}

void convolveRows(KernelIsa isa, const ConvRows& task) {
    switch (isa) {
#if GLINT_HAVE_AVX2
        case KernelIsa::Avx2:
            return avx2::convolveRows(task);
        case KernelIsa::Avx512:
            return avx512::convolveRows(task);
#endif
#if GLINT_HAVE_SIMD128
        case KernelIsa::Simd128:
            return simd128::convolveRows(task);
#endif
        default:
            return portable::convolveRows(task);
    }
}

int taskBlocks(KernelIsa isa) { return isa == KernelIsa::Avx512 ? 4 : 2; }

}  // namespace glint::unet
