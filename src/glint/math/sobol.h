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

#include "glint/math/sampling.h"

namespace glint {

namespace sobol {

constexpr uint32_t reverseBits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
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
constexpr uint32_t secondDimension(uint32_t index) {
    uint32_t v = 1u << 31, r = 0;
    for (; index; index >>= 1, v ^= v >> 1)
        if (index & 1) r ^= v;
    return r;
}

constexpr uint32_t hash32(uint64_t v) {
    v ^= v >> 33;
    v *= 0xff51afd7ed558ccdULL;
    v ^= v >> 33;
    v *= 0xc4ceb9fe1a85ec53ULL;
    v ^= v >> 33;
    return static_cast<uint32_t>(v);
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
        uint64_t dimSeed = seed_ ^ (0x9e3779b97f4a7c15ULL * (++dimension_));
        uint32_t i = sobol::owenScramble(index_, sobol::hash32(dimSeed));
        uint32_t x = sobol::owenScramble(sobol::reverseBits(i), sobol::hash32(dimSeed + 1));
        uint32_t y = sobol::owenScramble(sobol::secondDimension(i), sobol::hash32(dimSeed + 2));
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
