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

  private:
    uint64_t state_ = 0;
    uint64_t inc_ = 0;
};

}  // namespace glint
