#pragma once
/// Low-discrepancy sample values for Monte Carlo integrators: Owen-scrambled Sobol points,
/// padded dimension pair by dimension pair, after Burley, "Practical Hash-based Owen
/// Scrambling" (JCGT 9(4), 2020).
///
/// Each pair of dimensions a path asks for (the light to sample and where on it, the BSDF
/// lobe and direction, Russian roulette, ...) is the first two dimensions of the Sobol
/// sequence, a (0, 2)-sequence in base 2: the first 2^k samples of a pixel fall one in each
/// elementary interval of area 2^-k, for every k. The pair is shuffled (the sample index
/// scrambled by a nested uniform permutation) and Owen-scrambled with seeds hashed from the
/// pixel's seed and the dimension, so pairs are independent of one another and of other
/// pixels, and each stays a (0, 2)-sequence. Values depend only on (pixel seed, sample index,
/// dimension): never on the thread or the order in which samples are taken.

#include <cstdint>

#include "glint/math/rng.h"
#include "glint/math/sampling.h"

namespace glint {

namespace sobol {

constexpr uint32_t reverseBits(uint32_t x) {
    // Bits within bytes, then the bytes (one instruction).
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    return __builtin_bswap32(x);
}

/// Laine and Karras's hash, which permutes bit i depending only on bits below it.
constexpr uint32_t laineKarras(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/// A nested uniform (Owen) scramble of the 32-bit fraction x: each bit flipped depending on
/// the bits above it.
constexpr uint32_t owenScramble(uint32_t x, uint32_t seed) {
    return reverseBits(laineKarras(reverseBits(x), seed));
}

/// The Sobol sequence's second dimension as a 32-bit fraction: its direction numbers are
/// v_0 = 2^31, v_{i+1} = v_i xor (v_i >> 1) (the Pascal matrix mod 2). The first dimension is
/// reverseBits(index) (van der Corput).
constexpr uint32_t secondDimensionByBits(uint32_t index) {
    uint32_t v = 1u << 31, r = 0;
    for (; index; index >>= 1, v ^= v >> 1)
        if (index & 1) r ^= v;
    return r;
}

/// secondDimensionByBits() of each byte value at each byte position: the sequence is linear
/// over GF(2), so the value of an index is the xor of its bytes' values.
struct SecondDimensionTable {
    uint32_t byByte[4][256] = {};
    constexpr SecondDimensionTable() {
        for (int b = 0; b < 4; ++b)
            for (uint32_t v = 0; v < 256; ++v) byByte[b][v] = secondDimensionByBits(v << (8 * b));
    }
};
inline constexpr SecondDimensionTable kSecondDimension{};

inline uint32_t secondDimension(uint32_t index) {
    const auto& t = kSecondDimension.byByte;
    return t[0][index & 255] ^ t[1][(index >> 8) & 255] ^ t[2][(index >> 16) & 255] ^
           t[3][index >> 24];
}

constexpr double toUnit(uint32_t x) { return x * 0x1p-32; }

}  // namespace sobol

/// The sample values of one camera sample (pixel seed, index within the pixel), drawn
/// dimension pair by dimension pair in the order the integrator asks for them.
class SobolSampler {
  public:
    SobolSampler(uint64_t pixelSeed, uint32_t sampleIndex)
        : seed_(pixelSeed), index_(sampleIndex) {}

    /// The next pair of dimensions: a point of [0, 1)^2.
    Point2 get2D() {
        // One 64-bit hash gives the pair's three scrambling seeds (the third is the first
        // rotated: the Laine-Karras hash mixes it anew after the addition).
        uint64_t h = mixBits(seed_ + 0x9e3779b97f4a7c15ULL * (++dimension_));
        uint32_t s0 = static_cast<uint32_t>(h), s1 = static_cast<uint32_t>(h >> 32);
        uint32_t s2 = s0 ^ ((s1 << 16) | (s1 >> 16)) ^ 0x5bd1e995u;
        uint32_t i = sobol::owenScramble(index_, s0);
        // reverseBits(i) scrambled is laineKarras of i itself, reversed: one reversal saved.
        uint32_t x = sobol::reverseBits(sobol::laineKarras(i, s1));
        uint32_t y = sobol::owenScramble(sobol::secondDimension(i), s2);
        return {sobol::toUnit(x), sobol::toUnit(y)};
    }
    /// The next dimension alone: the first of a pair (a stratified 1D sequence itself).
    double get1D() { return get2D().x; }

  private:
    uint64_t seed_;
    uint32_t index_;
    uint64_t dimension_ = 0;
};

}  // namespace glint
