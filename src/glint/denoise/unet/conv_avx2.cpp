// The U-Net's convolution kernels with AVX2 and FMA (blocked.h): a block is one 256-bit
// register; a tile of 6 pixels by 2 blocks keeps 12 accumulators in the 16 registers, with the
// two blocks' weights and a broadcast input value beside them. Every header is included first,
// for the baseline instruction set; only the code below the target pragma, in its own
// namespace, may use AVX2 (as accel/bvh_isa_avx2.cpp explains).

#include <immintrin.h>

#include "glint/denoise/unet/blocked.h"

#pragma GCC push_options
#pragma GCC target("avx2,fma")

namespace glint::unet::avx2 {
namespace {

struct Ops {
    using B = __m256;
    using Block = Ops;
    static constexpr int kLanes = 8;
    static constexpr int kPixels[2] = {12, 6};
    static B load(const float* p) { return _mm256_loadu_ps(p); }
    static void store(float* const* blocks, size_t offset, B b) {
        _mm256_storeu_ps(blocks[0] + offset, b);
    }
    static B splat(const float* p) { return _mm256_broadcast_ss(p); }
    static B madd(B w, B v, B acc) { return _mm256_fmadd_ps(w, v, acc); }
    static B max(B a, B b) { return _mm256_max_ps(a, b); }
    static B zero() { return _mm256_setzero_ps(); }
};

#include "glint/denoise/unet/conv_kernels.inl"

}  // namespace

void convolveRows(const ConvRows& task) { rows<Ops>(task); }

}  // namespace glint::unet::avx2

#pragma GCC pop_options
