// The U-Net's convolution kernels with AVX-512 (blocked.h): a vector is two blocks, the 16
// outputs of a pair; a tile of 12 pixels by two vectors keeps 24 accumulators in the 32
// registers. A lone block (a layer of 8 outputs or fewer) and pooling take 256-bit registers.
// Each output sums the same products in the same order, each a fused multiply-add, as the AVX2
// kernels do: the two give the same bits. Headers first, as conv_avx2.cpp explains.

#include <immintrin.h>

#include "glint/denoise/unet/blocked.h"

#pragma GCC push_options
#pragma GCC target("avx512f,avx512vl,avx2,fma")
// GCC 12's own AVX-512 intrinsics pass _mm512_undefined_ps() to their masked builtins, which
// its -Wuninitialized reports as a use of an uninitialised value.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace glint::unet::avx512 {
namespace {

#include "glint/denoise/unet/ops_avx256.inl"

using Ops8 = Ops256<12, 12>;

struct Ops {
    using B = __m512;
    using Block = Ops8;
    static constexpr int kLanes = 16;
    static constexpr int kPixels[2] = {14, 12};
    static B load(const float* p) { return _mm512_loadu_ps(p); }
    static void store(float* const* blocks, size_t offset, B b) {
        _mm256_storeu_ps(blocks[0] + offset, _mm512_castps512_ps256(b));
        _mm256_storeu_ps(blocks[1] + offset,
                         _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(b), 1)));
    }
    static B splat(const float* p) { return _mm512_set1_ps(*p); }
    static B madd(B w, B v, B acc) { return _mm512_fmadd_ps(w, v, acc); }
    static B max(B a, B b) { return _mm512_max_ps(a, b); }
    static B zero() { return _mm512_setzero_ps(); }
};

#include "glint/denoise/unet/conv_kernels.inl"

}  // namespace

void convolveRows(const ConvRows& task) { rows<Ops>(task); }

}  // namespace glint::unet::avx512

#pragma GCC diagnostic pop
#pragma GCC pop_options
