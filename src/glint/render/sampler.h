#pragma once
/// Where the camera rays of a pixel go: stratified, jittered sub-pixel positions.
///
/// `spp` samples are spread over an a x b grid of equal cells (a * b = spp, a the largest
/// divisor of spp not above its square root), one uniformly jittered position per cell. With
/// one sample per pixel the position is the pixel centre, exactly as the course's renderer.
/// The jitter depends only on (pixel, seed), never on the thread that renders the pixel.

#include <cmath>
#include <cstdint>

#include "glint/math/rng.h"

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

class PixelSampler {
  public:
    PixelSampler(int spp, uint64_t seed) : spp_(spp < 1 ? 1 : spp), seed_(seed) {
        cols_ = 1;
        for (int a = 1; a * a <= spp_; ++a)
            if (spp_ % a == 0) cols_ = a;
        rows_ = spp_ / cols_;
    }

    int samplesPerPixel() const { return spp_; }

    /// Sample positions of pixel (x, y), in pixels from the image's top-left corner, passed
    /// to `f(px, py)` in a fixed order.
    template <typename F>
    void forEachSample(int x, int y, F&& f) const {
        if (spp_ == 1) {
            f(x + 0.5, y + 0.5);
            return;
        }
        Rng rng(
            mixBits(seed_ ^ mixBits((static_cast<uint64_t>(y) << 32) | static_cast<uint32_t>(x))));
        for (int j = 0; j < rows_; ++j)
            for (int i = 0; i < cols_; ++i) {
                double u = (i + static_cast<double>(rng.uniform())) / cols_;
                double v = (j + static_cast<double>(rng.uniform())) / rows_;
                f(x + u, y + v);
            }
    }

  private:
    int spp_, cols_ = 1, rows_ = 1;
    uint64_t seed_;
};

}  // namespace glint
