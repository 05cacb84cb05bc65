#include "glint/render/film/filter.h"

#include <algorithm>
#include <cmath>

namespace glint {

FilterSampler::FilterSampler(const FilterSpec& spec) : spec_(spec) {
    if (spec_.kind == FilterSpec::Kind::Box) return;
    // Tabulate the CDF of the profile (trapezoids on a fine grid); sample() inverts it with
    // linear interpolation within a cell (a piecewise-constant fit of 256 steps).
    double step = 2 * spec_.radius / kTable;
    cdf_[0] = 0;
    for (int i = 1; i <= kTable; ++i) {
        double x0 = -spec_.radius + step * (i - 1), x1 = x0 + step;
        cdf_[i] = cdf_[i - 1] + 0.5 * (profile(x0) + profile(x1)) * step;
    }
    for (double& c : cdf_) c /= cdf_[kTable];
}

double FilterSampler::profile(double x) const {
    double r = spec_.radius;
    if (!(std::abs(x) <= r)) return 0;
    if (spec_.kind == FilterSpec::Kind::Box) return 1;
    double sigma = r / 3;
    return std::exp(-x * x / (2 * sigma * sigma));
}

double FilterSampler::sample(double u) const {
    double r = spec_.radius;
    if (spec_.kind == FilterSpec::Kind::Box) return (2 * u - 1) * r;
    // The cell holding u, then linear within it.
    auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    int i = std::clamp(static_cast<int>(it - cdf_.begin()) - 1, 0, kTable - 1);
    double width = cdf_[i + 1] - cdf_[i];
    double f = width > 0 ? (u - cdf_[i]) / width : 0.5;
    double step = 2 * r / kTable;
    return std::clamp(-r + step * (i + f), -r, r);
}

}  // namespace glint
