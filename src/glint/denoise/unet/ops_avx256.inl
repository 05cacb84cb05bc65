// The kernels' operations on 256-bit AVX vectors, one block (8 floats) each (conv_kernels.inl
// says what an Ops type provides): AVX2's only vector, and AVX-512's for a lone block and for
// pooling. Included by conv_avx2.cpp and conv_avx512.cpp inside their own target and anonymous
// namespace; P0 and P1 are the pixels per tile of one and of two vectors (kPixels), which differ
// with the registers each instruction set has.

template <int P0, int P1>
struct Ops256 {
    using B = __m256;
    using Block = Ops256;
    static constexpr int kLanes = 8;
    static constexpr int kPixels[2] = {P0, P1};
    static B load(const float* p) { return _mm256_loadu_ps(p); }
    static void store(float* const* blocks, size_t offset, B b) {
        _mm256_storeu_ps(blocks[0] + offset, b);
    }
    static B splat(const float* p) { return _mm256_broadcast_ss(p); }
    static B madd(B w, B v, B acc) { return _mm256_fmadd_ps(w, v, acc); }
    static B max(B a, B b) { return _mm256_max_ps(a, b); }
    static B zero() { return _mm256_setzero_ps(); }
};
