#pragma once
/// Small deterministic random number generator (PCG32, O'Neill 2014: XSH-RR output).

#include <cstdint>

namespace glint {

/// A well-mixed 64-bit hash (splitmix64's finaliser).
constexpr uint64_t mixBits(uint64_t v) {
    v ^= v >> 30;
    v *= 0xbf58476d1ce4e5b9ULL;
    v ^= v >> 27;
    v *= 0x94d049bb133111ebULL;
    v ^= v >> 31;
    return v;
}

class Rng {
  public:
    constexpr explicit Rng(uint64_t seed = 0x853c49e6748fea9bULL,
                           uint64_t stream = 0xda3e39cb94b95bdbULL) {
        inc_ = (stream << 1u) | 1u;
        state_ = 0;
        next();
        state_ += seed;
        next();
    }

    /// Uniform 32-bit integer.
    constexpr uint32_t next() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ULL + inc_;
        auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        auto rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
    }

    /// Uniform float in [0, 1).
    float uniform() { return static_cast<float>(next() >> 8) * 0x1p-24f; }

    /// Skips `delta` values in O(log delta) steps: the state is then the one `delta` calls of
    /// next() would leave. One step of the generator is the affine map s -> a s + c (mod
    /// 2^64); its n-th power is again affine, s -> A s + C, and is built by squaring: the
    /// map's powers of two are composed for the bits of `delta` that are set.
    constexpr void advance(uint64_t delta) {
        uint64_t a = 6364136223846793005ULL, c = inc_;  // the map for 2^k steps, k = 0 first
        uint64_t accA = 1, accC = 0;                    // the map for the bits done so far
        for (; delta; delta >>= 1) {
            if (delta & 1) {
                accA *= a;
                accC = accC * a + c;
            }
            c = (a + 1) * c;  // (a s + c) composed with itself: a^2 s + (a + 1) c
            a *= a;
        }
        state_ = accA * state_ + accC;
    }

  private:
    uint64_t state_ = 0;
    uint64_t inc_ = 0;
};

}  // namespace glint
