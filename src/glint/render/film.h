#pragma once
/// Images: the float film the renderer writes, and 8-bit images for output and comparison.

#include <cstdint>
#include <vector>

#include "glint/math/vec3.h"

namespace glint {

/// Linear RGB radiance per pixel, unclamped, in double: the 8-bit conversion floors, so
/// rounding to float first would move values that sit just below a level. Row 0 is the top.
class Film {
  public:
    Film() = default;
    Film(int width, int height)
        : width_(width), height_(height), pixels_(static_cast<size_t>(width) * height) {}

    int width() const { return width_; }
    int height() const { return height_; }
    Vec3& at(int x, int y) { return pixels_[static_cast<size_t>(y) * width_ + x]; }
    const Vec3& at(int x, int y) const { return pixels_[static_cast<size_t>(y) * width_ + x]; }

  private:
    int width_ = 0, height_ = 0;
    std::vector<Vec3> pixels_;
};

/// An 8-bit image with 1 (grey) or 3 (RGB) interleaved channels, row 0 at the top.
struct Image8 {
    int width = 0, height = 0, channels = 3;
    std::vector<uint8_t> data;

    uint8_t at(int x, int y, int c) const {
        return data[(static_cast<size_t>(y) * width + x) * channels + c];
    }
};

/// The course's conversion: clamp to [0, 1], then floor(255 * c). NaN becomes 0.
inline uint8_t toByte(double c) {
    if (!(c > 0)) return 0;
    if (c >= 1) return 255;
    return static_cast<uint8_t>(c * 255);
}

/// The film as 8-bit RGB, each channel converted by `byte(c)`.
template <typename ToByte>
Image8 toImage8With(const Film& film, ToByte byte) {
    Image8 img{film.width(), film.height(), 3, {}};
    img.data.resize(static_cast<size_t>(img.width) * img.height * 3);
    size_t i = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Vec3& c = film.at(x, y);
            img.data[i++] = byte(c.x);
            img.data[i++] = byte(c.y);
            img.data[i++] = byte(c.z);
        }
    return img;
}

/// The course's conversion of the whole film (toByte per channel).
Image8 toImage8(const Film& film);

}  // namespace glint
