#include "glint/math/sobol.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace glint {
namespace {

TEST(Sobol, BitReversalAndOwenScrambleArePermutations) {
    std::set<uint32_t> seen;
    for (uint32_t i = 0; i < 4096; ++i) {
        EXPECT_EQ(sobol::reverseBits(sobol::reverseBits(i * 2654435761u)), i * 2654435761u);
        seen.insert(sobol::owenScramble(i << 20, 12345) >> 20);
    }
    EXPECT_EQ(seen.size(), 4096u) << "the top 12 bits of 4096 stratified values stay stratified";
}

/// Whether the first 2^m points of a pixel's dimension pair form a (0, m, 2)-net: every
/// elementary interval of area 2^-m (2^a x 2^(m-a) cells) holds exactly one point.
void expectNet(uint64_t pixelSeed, int pair, int m) {
    const uint32_t n = 1u << m;
    std::vector<Point2> points;
    for (uint32_t i = 0; i < n; ++i) {
        SobolSampler s(pixelSeed, i);
        Point2 p;
        for (int d = 0; d <= pair; ++d) p = s.get2D();
        ASSERT_GE(p.x, 0);
        ASSERT_LT(p.x, 1);
        ASSERT_GE(p.y, 0);
        ASSERT_LT(p.y, 1);
        points.push_back(p);
    }
    for (int a = 0; a <= m; ++a) {
        std::vector<int> count(n, 0);
        for (const Point2& p : points) {
            uint32_t cx = static_cast<uint32_t>(p.x * (1u << a));
            uint32_t cy = static_cast<uint32_t>(p.y * (1u << (m - a)));
            ++count[cx * (1u << (m - a)) + cy];
        }
        for (uint32_t c = 0; c < n; ++c)
            ASSERT_EQ(count[c], 1) << "pair " << pair << ", 2^" << a << " x 2^" << m - a;
    }
}

TEST(Sobol, EveryDimensionPairIsAZeroTwoSequence) {
    for (int pair : {0, 1, 5, 17})
        for (int m : {0, 2, 5, 8}) expectNet(0x1234 + pair, pair, m);
}

TEST(Sobol, TheSecondDimensionByTableIsTheOneByBits) {
    uint32_t x = 1;
    for (int i = 0; i < 100000; ++i, x = x * 1664525u + 1013904223u)
        ASSERT_EQ(sobol::secondDimension(x), sobol::secondDimensionByBits(x)) << x;
    EXPECT_EQ(sobol::secondDimension(0), 0u);
    EXPECT_EQ(sobol::secondDimension(1), 0x80000000u);
    EXPECT_EQ(sobol::secondDimension(2), 0xc0000000u);
    EXPECT_EQ(sobol::secondDimension(3), 0x40000000u);
}

TEST(Sobol, PixelsAndDimensionsDiffer) {
    SobolSampler a(1, 0), b(2, 0);
    Point2 a0 = a.get2D(), a1 = a.get2D(), b0 = b.get2D();
    EXPECT_NE(a0.x, b0.x);
    EXPECT_NE(a0.x, a1.x);
    // The same (pixel, index) gives the same values: nothing depends on call order elsewhere.
    SobolSampler again(1, 0);
    EXPECT_EQ(again.get2D().x, a0.x);
}

TEST(Sobol, PairsAreUncorrelated) {
    // The mean of x_pair0 * x_pair1 over many pixels is 1/4 for independent uniform values.
    double sum = 0;
    const int n = 65536;
    for (int i = 0; i < n; ++i) {
        SobolSampler s(static_cast<uint64_t>(i) * 0x9e3779b97f4a7c15ULL, 3);
        double x = s.get1D(), y = s.get1D();
        sum += (x - 0.5) * (y - 0.5);
    }
    // Standard deviation of (x - 1/2)(y - 1/2) is 1/12: 5 standard errors.
    EXPECT_NEAR(sum / n, 0, 5.0 / 12 / std::sqrt(n));
}

}  // namespace
}  // namespace glint
