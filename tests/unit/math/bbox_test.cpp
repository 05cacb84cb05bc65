#include "glint/math/bbox.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(Bounds3f, EnclosingRoundsOutwardsToTheNearestFloats) {
    Vec3 lo{0.1, -0.1, 1.0 / 3}, hi{0.3, 2.0 / 3, 1e-20};
    Bounds3f b = Bounds3f::enclosing(lo, hi);
    for (int a = 0; a < 3; ++a) {
        SCOPED_TRACE(a);
        // Contains the double box ...
        EXPECT_LE(static_cast<double>(b.lo[a]), lo[a]);
        EXPECT_GE(static_cast<double>(b.hi[a]), hi[a]);
        // ... and is the tightest float box that does.
        EXPECT_GT(static_cast<double>(std::nextafter(b.lo[a], kInf)), lo[a]);
        EXPECT_LT(static_cast<double>(std::nextafter(b.hi[a], -kInf)), hi[a]);
    }
}

TEST(Bounds3f, EnclosingKeepsExactlyRepresentableValues) {
    Bounds3f b = Bounds3f::enclosing({-1.5, 0, 0.25}, {2, 1024, 0.75});
    EXPECT_EQ(b.lo, Vec3f(-1.5f, 0, 0.25f));
    EXPECT_EQ(b.hi, Vec3f(2, 1024, 0.75f));
}

TEST(Bounds3f, EnclosingContainsValuesBeyondFloatPrecision) {
    // 1 + 2^-30 rounds to 1 in float: the upper bound must move up by one ulp.
    double justAbove = 1 + std::ldexp(1.0, -30), justBelow = 1 - std::ldexp(1.0, -30);
    Bounds3f b = Bounds3f::enclosing({justBelow, justBelow, 1}, {justAbove, justAbove, 1});
    EXPECT_EQ(b.hi.x, std::nextafter(1.0f, 2.0f));
    EXPECT_EQ(b.lo.x, std::nextafter(1.0f, 0.0f));
    EXPECT_EQ(b.lo.z, 1.0f);
    EXPECT_EQ(b.hi.z, 1.0f);
    // Large magnitudes and points (lo == hi) are handled alike.
    Bounds3f big = Bounds3f::enclosing({1e30, -1e30, 16777217}, {1e30, -1e30, 16777217});
    for (int a = 0; a < 3; ++a) EXPECT_LE(big.lo[a], big.hi[a]);
    EXPECT_LE(static_cast<double>(big.lo.z), 16777217.0);
    EXPECT_GE(static_cast<double>(big.hi.z), 16777217.0);
}

TEST(Bounds3f, DefaultBoxIsEmptyWithZeroArea) {
    Bounds3f b;
    EXPECT_TRUE(b.empty());
    EXPECT_EQ(b.area(), 0.0f);
    b.extend(Vec3f(1, 2, 3));
    EXPECT_FALSE(b.empty());
    EXPECT_EQ(b.area(), 0.0f);  // a point
    EXPECT_EQ(b.lo, Vec3f(1, 2, 3));
    EXPECT_EQ(b.hi, Vec3f(1, 2, 3));
    // An inverted box in one axis is empty.
    Bounds3f inverted{{0, 0, 0}, {1, -1, 1}};
    EXPECT_TRUE(inverted.empty());
    EXPECT_EQ(inverted.area(), 0.0f);
}

TEST(Bounds3f, AreaIsTheSurfaceArea) {
    Bounds3f b{{0, 0, 0}, {1, 2, 3}};
    EXPECT_FLOAT_EQ(b.area(), 2 * (1 * 2 + 2 * 3 + 3 * 1));
    Bounds3f flat{{-1, -1, 5}, {1, 1, 5}};  // a 2 x 2 square: both faces count
    EXPECT_FLOAT_EQ(flat.area(), 8);
}

TEST(Bounds3f, ExtendIsTheUnion) {
    Bounds3f a{{0, 0, 0}, {1, 1, 1}};
    a.extend(Bounds3f{{-1, 0.5, 0.5}, {0.5, 3, 0.5}});
    EXPECT_EQ(a.lo, Vec3f(-1, 0, 0));
    EXPECT_EQ(a.hi, Vec3f(1, 3, 1));
    // Extending by an empty box changes nothing.
    a.extend(Bounds3f{});
    EXPECT_EQ(a.lo, Vec3f(-1, 0, 0));
    EXPECT_EQ(a.hi, Vec3f(1, 3, 1));
    EXPECT_EQ(a.diagonal(), Vec3f(2, 3, 1));
    EXPECT_EQ(a.centroid(), Vec3f(0, 1.5f, 0.5f));
}

TEST(Bounds3f, LongestAxisIsTheLargestExtent) {
    EXPECT_EQ((Bounds3f{{0, 0, 0}, {3, 1, 2}}.longestAxis()), 0);
    EXPECT_EQ((Bounds3f{{0, 0, 0}, {1, 3, 2}}.longestAxis()), 1);
    EXPECT_EQ((Bounds3f{{0, 0, 0}, {1, 2, 3}}.longestAxis()), 2);
    EXPECT_EQ((Bounds3f{{-5, 0, 0}, {-4, 0, 0.5}}.longestAxis()), 0);
    // Ties go to the lower axis.
    EXPECT_EQ((Bounds3f{{0, 0, 0}, {2, 2, 1}}.longestAxis()), 0);
    EXPECT_EQ((Bounds3f{{0, 0, 0}, {1, 2, 2}}.longestAxis()), 1);
}

}  // namespace
}  // namespace glint
