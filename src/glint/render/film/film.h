#pragma once
/// Images: the float film the renderer writes, and 8-bit images for output and comparison.

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
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
    /// A film holding `pixels`, row by row (width * height of them).
    Film(int width, int height, std::vector<Vec3> pixels)
        : width_(width), height_(height), pixels_(std::move(pixels)) {}

    int width() const { return width_; }
    int height() const { return height_; }
    Vec3& at(int x, int y) { return pixels_[static_cast<size_t>(y) * width_ + x]; }
    const Vec3& at(int x, int y) const { return pixels_[static_cast<size_t>(y) * width_ + x]; }
    /// Every pixel, row by row from the top.
    const std::vector<Vec3>& pixels() const { return pixels_; }

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

/// Render passes (AOVs) of an image, resolved, row 0 at the top, width x height each (all empty
/// when the render kept none). Of each pixel's camera samples, averaged over them:
///  - albedo: the reflectance of the first surface the path meets that is not a perfect mirror
///    or smooth glass (chains of those are followed, as denoisers expect: glass along its more
///    likely branch, whichever the path took), times the chain's tint; 0 where the path leaves
///    the scene;
///  - normal: that surface's shading normal in world space, turned to face the ray (averaged,
///    so of length 1 or less; 0 where there is no surface);
///  - depth: the distance from the camera to the first surface hit, averaged over the samples
///    that hit one; 0 where none did;
///  - variance: per channel, the variance of the pixel's value as an estimate (the sample
///    variance over the samples, divided by their number); 0 with fewer than two samples;
///  - albedoVariance: the same for the albedo pass: where the samples of a pixel see different
///    surfaces at random (an alpha-blended surface, the reflection or the refraction of glass)
///    the albedo is noisy, and the denoiser filters it (written with the variance pass).
struct RenderPasses {
    int width = 0, height = 0;
    std::vector<Vec3> albedo, normal, variance, albedoVariance;
    std::vector<double> depth;

    RenderPasses() = default;
    /// Every pass of width x height pixels, all zero.
    RenderPasses(int w, int h)
        : width(w),
          height(h),
          albedo(size(w, h)),
          normal(size(w, h)),
          variance(size(w, h)),
          albedoVariance(size(w, h)),
          depth(size(w, h)) {}

    /// No pass at all (a file may hold some passes and not others: those are empty).
    bool empty() const {
        return albedo.empty() && normal.empty() && variance.empty() && albedoVariance.empty() &&
               depth.empty();
    }
    size_t index(int x, int y) const { return static_cast<size_t>(y) * width + x; }

  private:
    static size_t size(int w, int h) { return static_cast<size_t>(w) * static_cast<size_t>(h); }
};

/// Which render passes to write beside the beauty image (`--aov albedo,normal,depth,variance`).
struct AovSelection {
    bool albedo = false, normal = false, depth = false, variance = false;

    bool any() const { return albedo || normal || depth || variance; }
    static AovSelection all() { return {true, true, true, true}; }
    bool operator==(const AovSelection&) const = default;
};

/// Parses `--aov`'s list ("albedo,normal", or "all") into `out`; returns what is wrong, or an
/// empty string (`out` is then set).
std::string parseAovList(const std::string& text, AovSelection& out);
/// The list that parseAovList reads back: "albedo,normal,depth,variance" in that order; empty
/// for none.
std::string aovListText(const AovSelection& aovs);

/// What one camera sample reports for the passes (see RenderPasses): the integrator fills it.
struct SamplePasses {
    Vec3 albedo{0}, normal{0};
    double depth = 0;  ///< 0: the camera ray hit nothing.
};

/// The per-pixel sums behind the passes: added over samples (and over pieces) like the beauty's.
struct PassSums {
    Vec3 squares{0};  ///< Of the samples' radiance, per channel (for the variance).
    Vec3 albedo{0}, normal{0};
    Vec3 albedoSquares{0};       ///< Of the samples' albedo (for its variance).
    double depth = 0, hits = 0;  ///< Depths of the samples that hit something, and their number.

    void addSample(const Vec3& radiance, const SamplePasses& s) {
        squares += radiance * radiance;
        albedo += s.albedo;
        albedoSquares += s.albedo * s.albedo;
        normal += s.normal;
        if (s.depth > 0) {
            depth += s.depth;
            hits += 1;
        }
    }
    PassSums& operator+=(const PassSums& o) {
        squares += o.squares;
        albedo += o.albedo;
        normal += o.normal;
        albedoSquares += o.albedoSquares;
        depth += o.depth;
        hits += o.hits;
        return *this;
    }
};

/// A pixel's sum of sample values, kept as an unevaluated pair `hi + lo` (a double-double): each
/// addition puts its rounding error, computed exactly (Knuth's TwoSum), into `lo`. value()
/// rounds the pair once. So while the pair holds the sum exactly (its samples within about
/// 2^50 of the sum in magnitude; 106 bits in all), value() is the sum of the samples correctly
/// rounded, whatever the order or grouping in which they were added: a single render's running
/// sum and the merge of pieces that each summed a range of the samples give the same double.
struct SampleSum {
    Vec3 hi{0}, lo{0};

    SampleSum() = default;
    explicit SampleSum(const Vec3& v) : hi(v) {}

    /// Adds one value (a sample's radiance, or light from a pass of its own).
    void add(const Vec3& v) {
        for (int c = 0; c < 3; ++c) addTo(hi[c], lo[c], v[c]);
    }
    /// Adds another pair (a piece's sums): its high part, then its low part.
    void add(const SampleSum& o) {
        for (int c = 0; c < 3; ++c) {
            addTo(hi[c], lo[c], o.hi[c]);
            lo[c] += o.lo[c];
        }
    }
    /// The sum, rounded once.
    Vec3 value() const { return hi + lo; }

  private:
    /// hi + x into hi, its exact rounding error into lo. An infinite or NaN sum keeps the
    /// error out (it would be NaN): it stays in hi as the plain sum would.
    static void addTo(double& hi, double& lo, double x) {
        const double s = hi + x;
        if (std::isfinite(s)) {
            const double xPart = s - hi;
            lo += (hi - (s - xPart)) + (x - xPart);
        }
        hi = s;
    }
};

/// What a render of part of a frame keeps so that parts add up to the whole image: per pixel
/// the sum of its samples' values and their weight, the number of samples (each weighs 1: the
/// reconstruction filter is importance-sampled, render/film/sampler.h). Pixels a part did not render
/// have weight 0. Parts are pixel bounds, tile rows or sample ranges (docs/scale-out.md).
class FilmSums {
  public:
    FilmSums() = default;
    FilmSums(int width, int height)
        : width_(width), height_(height), sums_(size()), weights_(size()) {}

    int width() const { return width_; }
    int height() const { return height_; }
    SampleSum& sum(int x, int y) { return sums_[index(x, y)]; }
    const SampleSum& sum(int x, int y) const { return sums_[index(x, y)]; }
    double& weight(int x, int y) { return weights_[index(x, y)]; }
    double weight(int x, int y) const { return weights_[index(x, y)]; }

    /// Whether the sums behind the render passes are kept too (a render that makes passes).
    bool hasPasses() const { return !passes_.empty(); }
    /// Keeps them from now on (all zero).
    void keepPasses() { passes_.assign(size(), PassSums{}); }
    /// Keeps them no more.
    void dropPasses() { passes_ = {}; }
    PassSums& passes(int x, int y) { return passes_[index(x, y)]; }
    const PassSums& passes(int x, int y) const { return passes_[index(x, y)]; }

    /// Adds `other` (the same size) pixel by pixel: the sums of pieces that cover disjoint
    /// pixels are those pieces' own, exactly (x + 0 = x), and those of sample ranges the sums
    /// of all their samples (SampleSum). The passes' sums are added where both have them.
    void add(const FilmSums& other);

    /// The image: sum / weight per pixel, computed as the renderer computes it (the sum times
    /// 1 / weight; a single sample as it is), so that a frame merged from pieces that each
    /// rendered whole pixels is the single render's bit for bit. Weight 0 gives black.
    Film resolve() const;

    /// The render passes of these sums (empty if they have none).
    RenderPasses resolvePasses() const;

  private:
    size_t size() const { return static_cast<size_t>(width_) * static_cast<size_t>(height_); }
    size_t index(int x, int y) const { return static_cast<size_t>(y) * width_ + x; }
    int width_ = 0, height_ = 0;
    std::vector<SampleSum> sums_;
    std::vector<double> weights_;
    std::vector<PassSums> passes_;  ///< Empty: none kept.
};

/// The resolved passes of a pixel of `n` samples summing to `sum` with pass sums `p`, written
/// into `out` at index i.
void resolvePassesAt(const Vec3& sum, double n, const PassSums& p, RenderPasses& out, size_t i);

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
