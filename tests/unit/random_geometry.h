#pragma once
/// Seeded random numbers, points and directions for tests of geometry and traversal. No test
/// framework here: the web build's kernel test (tests/web/kernels_test.cpp) uses it too.

#include <cmath>
#include <cstdint>

#include "glint/math/rng.h"
#include "glint/math/vec3.h"

namespace glint::test {

class Random {
  public:
    explicit Random(uint64_t seed) : rng_(seed) {}
    double uni(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(rng_.uniform());
    }
    Vec3 point(double lo, double hi) { return {uni(lo, hi), uni(lo, hi), uni(lo, hi)}; }
    /// A uniformly distributed unit vector.
    Vec3 direction() {
        for (;;) {
            Vec3 v = point(-1, 1);
            double l2 = dot(v, v);
            if (l2 > 1e-4 && l2 <= 1) return v / std::sqrt(l2);
        }
    }
    uint32_t below(uint32_t n) { return static_cast<uint32_t>(rng_.next() % n); }

  private:
    Rng rng_;
};

}  // namespace glint::test
