// The U-Net's convolution kernels (blocked.h), written once over an instruction set's vector
// operations and included by each conv_*.cpp inside its own namespace and target. A vector
// holds one block (8 floats) or two (16); an `Ops` type provides, for its vector B:
//
//   Ops::kLanes                        8 or 16: floats per vector (kLanes / 8 blocks)
//   Ops::load(p)                       kLanes floats at p
//   Ops::store(blocks, offset, b)      each block of b at blocks[i] + offset
//   Ops::splat(p)                      the float at p in every lane
//   Ops::madd(w, v, acc)               acc + w * v
//   Ops::max(a, b), Ops::zero()
//   Ops::kPixels[nv]                   pixels per tile of nv + 1 vectors, so that the 
//                                      accumulators (nv + 1) x kPixels fit the registers with
//                                      the weights and a broadcast value beside them; even
//   Ops::Block                         the Ops of one block (itself if kLanes is 8): for a lone
//                                      block, and for pooling
//
// Included inside an anonymous namespace. A tile is P consecutive pixels of one output row for NV vectors of output channels: the
// accumulators stay in registers while every input block, tap and channel is summed in.

#define GLINT_UNROLL _Pragma("GCC unroll 16")

/// One input block's tap for a tile of P pixels by NV vectors: the weights of the block's 8
/// channels (w[v] + c * width) times the P pixels at `src`, pixel p at src + at(p) * kBlock,
/// where at(p) is p (kPattern 0), p >> 1 (1) or (p + 1) >> 1 (2): a source of the tile's size,
/// or one upsampled (half size, each pixel read twice).
template <class O, int P, int NV, int kPattern>
[[gnu::always_inline]] inline void tap(typename O::B (&acc)[P][NV], const float* const* w,
                                       int width, const float* src) {
    // Opaque to the compiler: else it keeps values one tap loads for the next taps that load
    // them again (the upsampled sources), and spills the accumulators to make room.
    asm("" : "+r"(src));
    GLINT_UNROLL for (int c = 0; c < kBlock; ++c) {
        typename O::B wv[NV];
        GLINT_UNROLL for (int v = 0; v < NV; ++v) wv[v] = O::load(w[v] + c * width);
        GLINT_UNROLL for (int p = 0; p < P; ++p) {
            const int at = kPattern == 0 ? p : kPattern == 1 ? p >> 1 : (p + 1) >> 1;
            const typename O::B in = O::splat(src + at * kBlock + c);
            GLINT_UNROLL for (int v = 0; v < NV; ++v) acc[p][v] = O::madd(wv[v], in, acc[p][v]);
        }
    }
}

/// Output row y's pixels [x, x + P) for the blocks [block, block + NV * kLanes / 8), ReLU
/// applied, written at dst[i] + p * kBlock for the i-th block. x is even (so an upsampled
/// source's pixels are known at compile time).
template <class O, int P, int NV>
inline void tile(const ConvRows& t, int block, int y, int x, float* const* dst) {
    using B = typename O::B;
    constexpr int kPerVector = O::kLanes / kBlock;
    const PackedConv& conv = *t.conv;
    // Vector v's weights: a pair's rows of 16 (two blocks, or one of a pair's blocks), every
    // vector of a tile with rows of the same width.
    const int width = conv.pairWidth(block);
    const float* w[NV];
    GLINT_UNROLL for (int v = 0; v < NV; ++v) {
        const int b = block + v * kPerVector;
        w[v] = conv.pairWeights(b) + (kPerVector == 1 ? (b % 2) * kBlock : 0);
    }
    B acc[P][NV];
    GLINT_UNROLL for (int v = 0; v < NV; ++v) {
        const B bias = O::load(conv.bias.data() + (block + v * kPerVector) * kBlock);
        GLINT_UNROLL for (int p = 0; p < P; ++p) acc[p][v] = bias;
    }
    auto next = [&] {
        GLINT_UNROLL for (int v = 0; v < NV; ++v) w[v] += kBlock * width;
    };
    for (const ConvSource& s : t.sources) {
        const BlockedMap& m = *s.map;
        const size_t rows = m.rowStride();
        for (int b = 0; b < m.blocks; ++b)
            for (int ky = 0; ky < 3; ++ky) {
                if (!s.upsampled) {
                    // Tap (ky, kx) reads pixel (x + p + kx - 1, y + ky - 1).
                    const float* src = m.at(b, y - 1 - s.firstRow, x - 1) + ky * rows;
                    for (int kx = 0; kx < 3; ++kx, next())
                        tap<O, P, NV, 0>(acc, w, width, src + kx * kBlock);
                } else {
                    // Tap (ky, kx) reads the half-size pixel ((x + p + kx - 1) >> 1,
                    // (y + ky - 1) >> 1): with x even, (x >> 1) + ((p + kx - 1) >> 1), which
                    // for kx = 0 is one pixel left of (p + 1) >> 1.
                    const float* src = m.at(b, (y + ky - 1) >> 1, x >> 1);
                    for (int kx = 0; kx < 3; ++kx, next())
                        if (kx == 1)
                            tap<O, P, NV, 1>(acc, w, width, src);
                        else
                            tap<O, P, NV, 2>(acc, w, width, src + (kx / 2 - 1) * kBlock);
                }
            }
    }
    const B zero = O::zero();
    GLINT_UNROLL for (int p = 0; p < P; ++p)
        GLINT_UNROLL for (int v = 0; v < NV; ++v)
            O::store(dst + v * kPerVector, p * kBlock, O::max(acc[p][v], zero));
}

/// tile<O, P, NV> for the last `n` (< P) pixels of a row.
template <class O, int P, int NV>
inline void tail(const ConvRows& t, int block, int y, int x, float* const* dst, int n) {
    if constexpr (P > 1) {
        if (n == P - 1) return tile<O, P - 1, NV>(t, block, y, x, dst);
        tail<O, P - 1, NV>(t, block, y, x, dst, n);
    }
}

/// Output row y, every pixel, for NV vectors of blocks from `block`, into dst[i] + x * kBlock.
template <class O, int NV>
void row(const ConvRows& t, int block, int y, float* const* rows) {
    constexpr int P = O::kPixels[NV - 1];
    static_assert(P % 2 == 0);
    constexpr int kBlocks = NV * O::kLanes / kBlock;
    float* dst[kBlocks];
    int x = 0;
    for (; x + P <= t.width; x += P) {
        for (int i = 0; i < kBlocks; ++i) dst[i] = rows[i] + x * kBlock;
        tile<O, P, NV>(t, block, y, x, dst);
    }
    if (x == t.width) return;
    for (int i = 0; i < kBlocks; ++i) dst[i] = rows[i] + x * kBlock;
    tail<O, P, NV>(t, block, y, x, dst, t.width - x);
}

/// Output row y for all the task's blocks, block i into rows[i]: two vectors at a time, then
/// one, then a lone block.
template <class O>
void rowOfBlocks(const ConvRows& t, int y, float* const* rows) {
    constexpr int kPerVector = O::kLanes / kBlock;
    int i = 0;
    for (; i + 2 * kPerVector <= t.blocks; i += 2 * kPerVector) row<O, 2>(t, t.block + i, y, rows + i);
    for (; i + kPerVector <= t.blocks; i += kPerVector) row<O, 1>(t, t.block + i, y, rows + i);
    if constexpr (kPerVector > 1)
        for (; i < t.blocks; ++i) row<typename O::Block, 1>(t, t.block + i, y, rows + i);
}

template <class O>
void rows(const ConvRows& t) {
    constexpr int kMaxBlocks = 4;
    float* dst[kMaxBlocks];
    if (!t.pool) {
        for (int y = t.y0; y < t.y1; ++y) {
            for (int i = 0; i < t.blocks; ++i)
                dst[i] = t.out->at(t.block + i, y - t.outFirstRow, 0);
            rowOfBlocks<O>(t, y, dst);
        }
        return;
    }
    // Two rows into the scratch ([block][row][pixel]), then each 2x2 block's largest value.
    using Block = typename O::Block;
    const size_t rowFloats = static_cast<size_t>(t.width) * kBlock;
    for (int y = t.y0; y < t.y1; y += 2) {
        for (int r = 0; r < 2; ++r) {
            for (int i = 0; i < t.blocks; ++i) dst[i] = t.scratch + (2 * i + r) * rowFloats;
            rowOfBlocks<O>(t, y + r, dst);
        }
        for (int i = 0; i < t.blocks; ++i) {
            const float* top = t.scratch + 2 * i * rowFloats;
            const float* bottom = top + rowFloats;
            float* out = t.out->at(t.block + i, y / 2 - t.outFirstRow, 0);
            for (int x = 0; x < t.width / 2; ++x) {
                const int at = 2 * x * kBlock;
                const typename Block::B m =
                    Block::max(Block::max(Block::load(top + at), Block::load(top + at + kBlock)),
                               Block::max(Block::load(bottom + at), Block::load(bottom + at + kBlock)));
                Block::store(&out, x * kBlock, m);
            }
        }
    }
}

#undef GLINT_UNROLL
