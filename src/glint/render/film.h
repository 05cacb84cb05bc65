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

/// Pixel bounds [x0, x1) x [y0, y1) in pixels from the image's top-left corner: pbrt's
/// `--pixelbounds` convention, the upper bounds excluded. Empty: the whole image.
struct PixelBounds {
    int x0 = 0, x1 = 0, y0 = 0, y1 = 0;

    bool empty() const { return x1 <= x0 || y1 <= y0; }
    bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
    bool operator==(const PixelBounds&) const = default;
};

/// What a render of part of a frame keeps so that parts add up to the whole image: per pixel
/// the sum of its samples' values and their weight, the number of samples (each weighs 1: the
/// reconstruction filter is importance-sampled, render/sampler.h). Pixels a part did not render
/// have weight 0. Parts are pixel bounds, tile rows or sample ranges (docs/scale-out.md).
class FilmSums {
  public:
    FilmSums() = default;
    FilmSums(int width, int height)
        : width_(width), height_(height), sums_(size()), weights_(size()) {}

    int width() const { return width_; }
    int height() const { return height_; }
    Vec3& sum(int x, int y) { return sums_[index(x, y)]; }
    const Vec3& sum(int x, int y) const { return sums_[index(x, y)]; }
    double& weight(int x, int y) { return weights_[index(x, y)]; }
    double weight(int x, int y) const { return weights_[index(x, y)]; }

    /// Adds `other` (the same size) pixel by pixel: the sums of pieces that cover disjoint
    /// pixels are those pieces' own, exactly (x + 0 = x).
    void add(const FilmSums& other);

    /// The image: sum / weight per pixel, computed as the renderer computes it (the sum times
    /// 1 / weight; a single sample as it is), so that a frame merged from pieces that each
    /// rendered whole pixels is the single render's bit for bit. Weight 0 gives black.
    Film resolve() const;

  private:
    size_t size() const { return static_cast<size_t>(width_) * static_cast<size_t>(height_); }
    size_t index(int x, int y) const { return static_cast<size_t>(y) * width_ + x; }
    int width_ = 0, height_ = 0;
    std::vector<Vec3> sums_;
    std::vector<double> weights_;
};

/// The value of a pixel whose `n` samples sum to `sum`: the renderer's rule, shared with
/// FilmSums::resolve so that merged pieces reproduce it exactly.
inline Vec3 pixelValue(const Vec3& sum, double n) {
    if (!(n > 0)) return Vec3(0);
    return n == 1 ? sum : sum * (1.0 / n);
}

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
