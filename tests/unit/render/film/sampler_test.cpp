#include "glint/render/film/sampler.h"

#include <gtest/gtest.h>

#include <set>
#include <utility>
#include <vector>

namespace glint {
namespace {

std::vector<std::pair<double, double>> samples(const PixelSampler& s, int x, int y) {
    std::vector<std::pair<double, double>> out;
    s.forEachSample(x, y, [&](double px, double py) { out.emplace_back(px, py); });
    return out;
}

TEST(PixelSampler, OneSampleIsThePixelCentre) {
    auto s = samples(PixelSampler(1, 42), 7, 3);
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(s[0], std::make_pair(7.5, 3.5));
}

TEST(PixelSampler, EachStratumOfTheGridHoldsExactlyOneSample) {
    // 12 = 3 x 4: columns are the largest divisor not above sqrt(12).
    auto s = samples(PixelSampler(12, 1), 10, 20);
    ASSERT_EQ(s.size(), 12u);
    std::set<std::pair<int, int>> cells;
    for (auto [px, py] : s) {
        ASSERT_GE(px, 10.0);
        ASSERT_LT(px, 11.0);
        ASSERT_GE(py, 20.0);
        ASSERT_LT(py, 21.0);
        cells.insert({static_cast<int>((px - 10) * 3), static_cast<int>((py - 20) * 4)});
    }
    EXPECT_EQ(cells.size(), 12u);
}

TEST(PixelSampler, PrimeCountsUseOneRowOfStrata) {
    auto s = samples(PixelSampler(7, 1), 0, 0);
    std::set<int> rows;
    for (auto [px, py] : s) {
        EXPECT_GE(px, 0.0);
        EXPECT_LT(px, 1.0);
        rows.insert(static_cast<int>(py * 7));
    }
    EXPECT_EQ(rows.size(), 7u);
}

TEST(PixelSampler, JitterDependsOnPixelAndSeedOnly) {
    PixelSampler a(16, 5), b(16, 5), c(16, 6);
    EXPECT_EQ(samples(a, 3, 4), samples(b, 3, 4));
    EXPECT_NE(samples(a, 3, 4), samples(c, 3, 4));
    // Neighbouring pixels are not shifted copies of each other.
    auto p = samples(a, 3, 4), q = samples(a, 4, 4);
    EXPECT_NE(p[0].first - 3, q[0].first - 4);
}

}  // namespace
}  // namespace glint
