#pragma once
/// The denoiser's working images: one float channel per plane, with a border of replicated edge
/// pixels so that the filters read neighbours without bounds checks; and the fast exponential
/// its weights use. Internal to denoise/.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/math/bits.h"

namespace glint::denoise_detail {

/// A width x height float channel with `pad` extra pixels on every side; at(x, y) takes
/// x in [-pad, width + pad), y in [-pad, height + pad).
class Plane {
  public:
    Plane() = default;
    Plane(int width, int height, int pad)
        : width_(width),
          height_(height),
          pad_(pad),
          stride_(width + 2 * pad),
          data_(static_cast<size_t>(width + 2 * pad) * (height + 2 * pad), 0.0f) {}

    int width() const { return width_; }
    int height() const { return height_; }
    int pad() const { return pad_; }
    float* row(int y) { return data_.data() + static_cast<size_t>(y + pad_) * stride_ + pad_; }
    const float* row(int y) const {
        return data_.data() + static_cast<size_t>(y + pad_) * stride_ + pad_;
    }
    float& at(int x, int y) { return row(y)[x]; }
    float at(int x, int y) const { return row(y)[x]; }

    /// Fills the border with copies of the nearest edge pixel.
    void replicateBorder() {
        for (int y = 0; y < height_; ++y) {
            float* r = row(y);
            for (int x = -pad_; x < 0; ++x) r[x] = r[0];
            for (int x = width_; x < width_ + pad_; ++x) r[x] = r[width_ - 1];
        }
        for (int y = -pad_; y < 0; ++y) std::copy_n(row(0) - pad_, stride_, row(y) - pad_);
        for (int y = height_; y < height_ + pad_; ++y)
            std::copy_n(row(height_ - 1) - pad_, stride_, row(y) - pad_);
    }

  private:
    int width_ = 0, height_ = 0, pad_ = 0;
    size_t stride_ = 0;
    std::vector<float> data_;
};

/// e^-x for x in [0, 80], relative error below 2e-5: plain arithmetic and bit operations, so
/// that loops over it vectorise (clamp x in a loop of its own: a comparison here stops GCC) and
/// every platform gives the same bits.
inline float expNeg(float x) {
    float t = x * -1.44269504f;           // log2(e^-x), in [-115.5, 0]
    int i = static_cast<int>(t);          // towards zero: i >= t
    float f = t - static_cast<float>(i);  // in (-1, 0]
    // 2^f on [-1, 0]: a degree-6 polynomial.
    float p = 1.5403530e-4f;
    p = p * f + 1.3333558e-3f;
    p = p * f + 9.6181291e-3f;
    p = p * f + 5.5504109e-2f;
    p = p * f + 2.4022651e-1f;
    p = p * f + 6.9314718e-1f;
    p = p * f + 1.0f;
    return p * bitCast<float>(static_cast<int32_t>((i + 127) << 23));
}

}  // namespace glint::denoise_detail
