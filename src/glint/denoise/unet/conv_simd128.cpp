// The U-Net's convolution kernels with WebAssembly SIMD128 (blocked.h; the web build, always
// compiled with -msimd128): a block is two 4-wide vectors. Without relaxed SIMD there is no
// fused multiply-add: each is a multiply and an add, rounded twice, as the portable kernels do.

#include <wasm_simd128.h>

#include "glint/denoise/unet/blocked.h"

namespace glint::unet::simd128 {
namespace {

struct Ops {
    struct B {
        v128_t lo, hi;
    };
    using Block = Ops;
    static constexpr int kLanes = 8;
    static constexpr int kPixels[2] = {4, 2};
    static B load(const float* p) { return {wasm_v128_load(p), wasm_v128_load(p + 4)}; }
    static void store(float* const* blocks, size_t offset, B b) {
        wasm_v128_store(blocks[0] + offset, b.lo);
        wasm_v128_store(blocks[0] + offset + 4, b.hi);
    }
    static B splat(const float* p) {
        const v128_t v = wasm_v128_load32_splat(p);
        return {v, v};
    }
    static B madd(B w, B v, B acc) {
        return {wasm_f32x4_add(acc.lo, wasm_f32x4_mul(w.lo, v.lo)),
                wasm_f32x4_add(acc.hi, wasm_f32x4_mul(w.hi, v.hi))};
    }
    // pmax(a, b) = a < b ? b : a, std::max's choice (accel/bvh_isa_simd128.cpp says why).
    static B max(B a, B b) { return {wasm_f32x4_pmax(a.lo, b.lo), wasm_f32x4_pmax(a.hi, b.hi)}; }
    static B zero() { return {wasm_f32x4_splat(0.f), wasm_f32x4_splat(0.f)}; }
};

#include "glint/denoise/unet/conv_kernels.inl"

}  // namespace

void convolveRows(const ConvRows& task) { rows<Ops>(task); }

}  // namespace glint::unet::simd128
