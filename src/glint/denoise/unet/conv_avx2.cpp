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

#include "glint/denoise/unet/ops_avx256.inl"

using Ops = Ops256<12, 6>;

#include "glint/denoise/unet/conv_kernels.inl"

}  // namespace

void convolveRows(const ConvRows& task) { rows<Ops>(task); }

}  // namespace glint::unet::avx2

#pragma GCC pop_options
