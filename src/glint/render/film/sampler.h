#pragma once
/// Where the camera rays of a pixel go: stratified, jittered sub-pixel positions.
///
/// `spp` samples are spread over an a x b grid of equal cells (a * b = spp, a the largest
/// divisor of spp not above its square root), one uniformly jittered position per cell. With
/// one sample per pixel the position is the pixel centre, exactly as the course's renderer.
/// The jitter depends only on (pixel, seed), never on the thread that renders the pixel.
///
/// With a reconstruction filter other than the one-pixel box, each jittered position u in the
/// pixel's unit square is mapped through the filter's inverse CDF per axis (filter.h), so the
/// samples spread over the filter's support, still stratified.
///
/// Progressive positions (for adaptive sampling, render/adaptive.h): sample k of a pixel is
/// point k of a 2D Owen-scrambled Sobol sequence seeded by the pixel, so that every prefix of a
/// pixel's samples is spread over it (the first 2^m in one elementary interval each), wherever
/// the pixel stops; the grid above spreads only the whole set.

#include <cmath>
#include <cstdint>

#include "glint/math/rng.h"
#include "glint/math/sobol.h"
#include "glint/render/film/filter.h"

namespace glint {

class PixelSampler {
  public:
    PixelSampler(int spp, uint64_t seed, const FilterSpec& filter = {}, bool progressive = false)
        : spp_(spp < 1 ? 1 : spp),
          seed_(seed),
          pixelBox_(filter == FilterSpec{}),
          progressive_(progressive),
          filter_(filter) {
        cols_ = 1;
        for (int a = 1; a * a <= spp_; ++a)
            if (spp_ % a == 0) cols_ = a;
        rows_ = spp_ / cols_;
    }

    int samplesPerPixel() const { return spp_; }

    /// Sample positions of pixel (x, y), in pixels from the image's top-left corner, passed
    /// to `f(px, py)` in a fixed order: samples [begin, end) of it (end < 0: all), exactly those
    /// that the whole sequence has there (the jitter's generator skips the ones before).
    template <typename F>
    void forEachSample(int x, int y, F&& f, int begin = 0, int end = -1) const {
        if (end < 0 || end > spp_) end = spp_;
        if (spp_ == 1) {
            if (begin < end) f(x + 0.5, y + 0.5);
            return;
        }
        if (progressive_) {
            const uint64_t positionSeed = mixBits(pixelSeed(x, y) ^ 0x2545f4914f6cdd1dULL);
            for (int k = begin; k < end; ++k) {
                const Point2 u = SobolSampler(positionSeed, static_cast<uint32_t>(k)).get2D();
                if (pixelBox_)
                    f(x + u.x, y + u.y);
                else
                    f(x + 0.5 + filter_.sample(u.x), y + 0.5 + filter_.sample(u.y));
            }
            return;
        }
        Rng rng(
            mixBits(seed_ ^ mixBits((static_cast<uint64_t>(y) << 32) | static_cast<uint32_t>(x))));
        if (begin > 0) rng.advance(2 * static_cast<uint64_t>(begin));  // two values a sample
        for (int k = begin; k < end; ++k) {
            const int i = k % cols_, j = k / cols_;
            double u = (i + static_cast<double>(rng.uniform())) / cols_;
            double v = (j + static_cast<double>(rng.uniform())) / rows_;
            if (pixelBox_)
                f(x + u, y + v);
            else
                f(x + 0.5 + filter_.sample(u), y + 0.5 + filter_.sample(v));
        }
    }

    /// Seed of pixel (x, y) for the low-discrepancy values its samples draw (math/sobol.h).
    uint64_t pixelSeed(int x, int y) const {
        uint64_t pixel = (static_cast<uint64_t>(y) << 32) | static_cast<uint32_t>(x);
        return mixBits(mixBits(seed_ ^ 0x632be59bd9b4e019ULL) ^ mixBits(pixel));
    }

    /// Seed of the random numbers that sample `index` of pixel (x, y) uses beyond its position
    /// (lens, lights, glossy reflection): a function of (pixel, sample, seed) only.
    uint64_t sampleSeed(int x, int y, int index) const {
        uint64_t pixel = (static_cast<uint64_t>(y) << 32) | static_cast<uint32_t>(x);
        return mixBits(mixBits(seed_ ^ 0x9e3779b97f4a7c15ULL) ^ mixBits(pixel) ^
                       static_cast<uint64_t>(index));
    }

  private:
    int spp_, cols_ = 1, rows_ = 1;
    uint64_t seed_;
    bool pixelBox_;     ///< The one-pixel box filter: positions stay in the pixel.
    bool progressive_;  ///< Sobol positions, spread in every prefix (see above).
    FilterSampler filter_;
};

}  // namespace glint
