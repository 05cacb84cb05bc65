// The U-Net's convolution kernels in portable C++ (blocked.h): plain loops over a block's 8
// floats, which the compiler vectorises as the target allows. Any machine runs them.

#include <algorithm>

#include "glint/denoise/unet/blocked.h"

namespace glint::unet::portable {
namespace {

struct Ops {
    struct B {
        float v[kBlock];
    };
    using Block = Ops;
    static constexpr int kLanes = kBlock;
    static constexpr int kPixels[2] = {4, 2};
    static B load(const float* p) {
        B b;
        for (int i = 0; i < kBlock; ++i) b.v[i] = p[i];
        return b;
    }
    static void store(float* const* blocks, size_t offset, const B& b) {
        for (int i = 0; i < kBlock; ++i) blocks[0][offset + i] = b.v[i];
    }
    static B splat(const float* p) {
        B b;
        for (int i = 0; i < kBlock; ++i) b.v[i] = *p;
        return b;
    }
    static B madd(const B& w, const B& v, const B& acc) {
        B r;
        for (int i = 0; i < kBlock; ++i) r.v[i] = acc.v[i] + w.v[i] * v.v[i];
        return r;
    }
    static B max(const B& a, const B& b) {
        B r;
        for (int i = 0; i < kBlock; ++i) r.v[i] = std::max(a.v[i], b.v[i]);
        return r;
    }
    static B zero() { return B{}; }
};

#include "glint/denoise/unet/conv_kernels.inl"

}  // namespace

void convolveRows(const ConvRows& task) { rows<Ops>(task); }

}  // namespace glint::unet::portable
