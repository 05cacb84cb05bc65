#pragma once
/// Pixel reconstruction filters, applied by importance sampling: each camera sample is placed
/// at an offset from the pixel centre drawn from the filter's own distribution and counts with
/// equal weight in its pixel alone. For filters that are never negative this gives the same
/// expected pixel value as weighting and splatting samples into neighbouring pixels, with no
/// shared writes between tiles, so images cannot depend on the thread count (the approach of
/// pbrt-v4, Pharr, Jakob and Humphreys, "Physically Based Rendering", 4th ed., section 8.8).

#include <array>

#include "glint/scene/filter_spec.h"

namespace glint {

/// The filter's separable 1D profile, f(x, y) = profile(x) * profile(y), and a sampler for it.
class FilterSampler {
  public:
    explicit FilterSampler(const FilterSpec& spec);

    /// Unnormalised profile at offset `x` pixels from the centre; 0 beyond the radius.
    double profile(double x) const;
    /// Offset in [-radius, radius] distributed in proportion to profile(x), for u in [0, 1);
    /// monotonic in u, so stratified u give stratified offsets.
    double sample(double u) const;

  private:
    static constexpr int kTable = 256;
    FilterSpec spec_;
    std::array<double, kTable + 1> cdf_{};  ///< CDF at x_i = -radius + 2 radius i / kTable.
};

}  // namespace glint
