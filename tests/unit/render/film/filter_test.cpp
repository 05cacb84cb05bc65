#include "glint/render/film/filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace glint {
namespace {

TEST(FilterSampler, BoxMapsTheUnitIntervalLinearlyOntoTheRadius) {
    FilterSampler box(FilterSpec{FilterSpec::Kind::Box, 0.5});
    EXPECT_DOUBLE_EQ(box.sample(0), -0.5);
    EXPECT_DOUBLE_EQ(box.sample(0.25), -0.25);
    EXPECT_DOUBLE_EQ(box.sample(0.5), 0);
    FilterSampler wide(FilterSpec{FilterSpec::Kind::Box, 1.5});
    EXPECT_DOUBLE_EQ(wide.sample(0.75), 0.75);
}

TEST(FilterSampler, GaussianSamplesAreMonotonicSymmetricAndWithinTheRadius) {
    FilterSampler g(FilterSpec{FilterSpec::Kind::Gaussian, 1.5});
    double last = -2;
    for (int i = 0; i <= 1000; ++i) {
        double u = std::min(i / 1000.0, 0.999999);
        double x = g.sample(u);
        EXPECT_GE(x, last);
        EXPECT_GE(x, -1.5);
        EXPECT_LE(x, 1.5);
        last = x;
    }
    EXPECT_NEAR(g.sample(0.5), 0, 1e-9);
    EXPECT_NEAR(g.sample(0.2), -g.sample(0.8), 1e-9);
}

TEST(FilterSampler, GaussianSamplesFollowTheProfile) {
    // Stratified u mapped through the sampler: the fraction of offsets in each bin of width
    // 0.25 matches the integral of the normalised profile over the bin.
    FilterSampler g(FilterSpec{FilterSpec::Kind::Gaussian, 1.5});
    const int n = 100000, bins = 12;
    std::vector<double> count(bins);
    for (int i = 0; i < n; ++i) {
        double x = g.sample((i + 0.5) / n);
        count[std::min(bins - 1, static_cast<int>((x + 1.5) / 0.25))] += 1.0 / n;
    }
    double total = 0;
    std::vector<double> mass(bins);
    for (int b = 0; b < bins; ++b) {
        for (int k = 0; k < 1000; ++k) mass[b] += g.profile(-1.5 + 0.25 * (b + (k + 0.5) / 1000));
        total += mass[b];
    }
    for (int b = 0; b < bins; ++b) EXPECT_NEAR(count[b], mass[b] / total, 2e-3) << "bin " << b;
    // sigma = radius / 3: about 68% within one sigma (0.5 px), a little more when truncated.
    double within = 0;
    for (int i = 0; i < n; ++i) within += std::abs(g.sample((i + 0.5) / n)) < 0.5 ? 1.0 / n : 0;
    EXPECT_NEAR(within, 0.6827 / 0.9973, 0.01);
}

}  // namespace
}  // namespace glint
