// Keyframed values (scene/keyframes.h) against values computed by hand from glTF's appendix C:
// each interpolation between and outside the keys, quaternion slerp along the shorter arc and
// its normalisation, cubic-spline tangents scaled by the key interval, and the tracks that are
// refused.

#include "glint/scene/keyframes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

namespace glint {
namespace {

using ::testing::HasSubstr;

KeyframeTrack track(std::vector<double> times, std::vector<double> values, size_t width,
                    Interpolation interpolation, bool rotation = false) {
    KeyframeTrack t;
    t.times = std::move(times);
    t.values = std::move(values);
    t.width = width;
    t.interpolation = interpolation;
    t.rotation = rotation;
    return t;
}

std::array<double, 4> at(const KeyframeTrack& t, double time) {
    std::array<double, 4> v{};
    t.sample(time, v.data());
    return v;
}

TEST(Keyframes, StepHoldsEachKeyUntilTheNext) {
    const auto t = track({0, 1, 3}, {10, 20, 30}, 1, Interpolation::Step);
    ASSERT_EQ(t.problem(), "");
    EXPECT_EQ(at(t, -5)[0], 10);  // before the first key: the first value
    EXPECT_EQ(at(t, 0)[0], 10);
    EXPECT_EQ(at(t, 0.999)[0], 10);
    EXPECT_EQ(at(t, 1)[0], 20);
    EXPECT_EQ(at(t, 2.5)[0], 20);
    EXPECT_EQ(at(t, 3)[0], 30);
    EXPECT_EQ(at(t, 100)[0], 30);  // after the last: the last
}

TEST(Keyframes, LinearInterpolatesEachComponent) {
    const auto t = track({1, 2, 4}, {0, 0, 0, 2, 4, -6, 2, 0, 10}, 3, Interpolation::Linear);
    ASSERT_EQ(t.problem(), "");
    auto v = at(t, 1.25);  // a quarter of the way from key 0 to key 1
    EXPECT_DOUBLE_EQ(v[0], 0.5);
    EXPECT_DOUBLE_EQ(v[1], 1);
    EXPECT_DOUBLE_EQ(v[2], -1.5);
    v = at(t, 3);  // halfway from key 1 (t 2) to key 2 (t 4)
    EXPECT_DOUBLE_EQ(v[0], 2);
    EXPECT_DOUBLE_EQ(v[1], 2);
    EXPECT_DOUBLE_EQ(v[2], 2);
    EXPECT_EQ(at(t, 0)[2], 0);
    EXPECT_EQ(at(t, 9)[2], 10);
}

TEST(Keyframes, LinearRotationsSlerpAlongTheShorterArc) {
    // From no rotation to 90 degrees about z: at a third of the time, 30 degrees about z.
    const double h = std::sqrt(0.5);
    const auto t = track({0, 3}, {0, 0, 0, 1, 0, 0, h, h}, 4, Interpolation::Linear, true);
    ASSERT_EQ(t.problem(), "");
    auto q = at(t, 1);
    const double half = std::numbers::pi / 12;  // half of 30 degrees
    EXPECT_NEAR(q[2], std::sin(half), 1e-12);
    EXPECT_NEAR(q[3], std::cos(half), 1e-12);
    EXPECT_NEAR(q[0], 0, 1e-12);
    // The same end rotation written as its negative (-q is the same rotation): the path still
    // turns 30 degrees the short way, not 150 the long way round.
    const auto negated = track({0, 3}, {0, 0, 0, 1, 0, 0, -h, -h}, 4, Interpolation::Linear, true);
    q = at(negated, 1);
    EXPECT_NEAR(std::abs(q[2]), std::sin(half), 1e-12);
    EXPECT_NEAR(std::abs(q[3]), std::cos(half), 1e-12);
    // Keys that are not unit length are normalised.
    const auto scaled = track({0, 1}, {0, 0, 0, 2, 0, 0, 0, 2}, 4, Interpolation::Linear, true);
    q = at(scaled, 0.5);
    EXPECT_NEAR(q[3], 1, 1e-12);
    q = at(scaled, -1);
    EXPECT_NEAR(q[3], 1, 1e-12);
}

TEST(Keyframes, CubicSplineUsesTheTangentsScaledByTheKeyInterval) {
    // Keys at t = 1 and t = 3 (d = 2): v0 = 1 with out-tangent b0 = 2, v1 = 5 with in-tangent
    // a1 = -1. Each key is (in-tangent, value, out-tangent).
    const auto t = track({1, 3}, {7, 1, 2, -1, 5, 9}, 1, Interpolation::CubicSpline);
    ASSERT_EQ(t.problem(), "");
    // At s = 0.5: h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = -0.125;
    // v = 0.5 * 1 + 2 * 0.125 * 2 + 0.5 * 5 + 2 * (-0.125) * (-1) = 0.5 + 0.5 + 2.5 + 0.25.
    EXPECT_DOUBLE_EQ(at(t, 2)[0], 3.75);
    // At s = 0.25: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875;
    // v = 0.84375 + 2 * 0.140625 * 2 + 0.15625 * 5 + 2 * (-0.046875) * (-1) = 2.28125.
    EXPECT_DOUBLE_EQ(at(t, 1.5)[0], 2.28125);
    // The keys themselves, and outside them: the values, never the tangents.
    EXPECT_DOUBLE_EQ(at(t, 1)[0], 1);
    EXPECT_DOUBLE_EQ(at(t, 3)[0], 5);
    EXPECT_DOUBLE_EQ(at(t, 0)[0], 1);
    EXPECT_DOUBLE_EQ(at(t, 4)[0], 5);
    // The slope at a key is the tangent: (v(1 + e) - v(1)) / e -> b0 = 2.
    const double e = 1e-6;
    EXPECT_NEAR((at(t, 1 + e)[0] - at(t, 1)[0]) / e, 2, 1e-4);
    EXPECT_NEAR((at(t, 3)[0] - at(t, 3 - e)[0]) / e, -1, 1e-4);
}

TEST(Keyframes, CubicSplineRotationsAreNormalised) {
    // Value keys of no rotation and 90 degrees about z, zero tangents: the spline between them
    // is not unit length, the result is.
    const double h = std::sqrt(0.5);
    const auto t =
        track({0, 1}, {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, h, h, 0, 0, 0, 0}, 4,
              Interpolation::CubicSpline, true);
    ASSERT_EQ(t.problem(), "");
    const auto q = at(t, 0.5);
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1, 1e-12);
    // Symmetric halfway: 45 degrees about z.
    EXPECT_NEAR(q[2], std::sin(std::numbers::pi / 8), 1e-12);
}

TEST(Keyframes, BadTracksSayWhatIsWrong) {
    EXPECT_THAT(track({}, {}, 3, Interpolation::Linear).problem(), HasSubstr("no keyframes"));
    EXPECT_THAT(track({0, 1, 1}, {0, 0, 0}, 1, Interpolation::Linear).problem(),
                HasSubstr("key times must increase, but time 2"));
    EXPECT_THAT(track({1, 0}, {0, 0}, 1, Interpolation::Step).problem(),
                HasSubstr("key times must increase"));
    EXPECT_THAT(track({0, NAN}, {0, 0}, 1, Interpolation::Linear).problem(),
                HasSubstr("key time 1 is not finite"));
    EXPECT_THAT(track({0, 1}, {0, 0, 0}, 1, Interpolation::Linear).problem(),
                HasSubstr("2 key times but 3 output values, where LINEAR needs 2"));
    EXPECT_THAT(track({0, 1}, {0, 0}, 1, Interpolation::CubicSpline).problem(),
                HasSubstr("where CUBICSPLINE needs 6"));
    EXPECT_THAT(track({0}, {INFINITY}, 1, Interpolation::Step).problem(),
                HasSubstr("output value 0 is not finite"));
    EXPECT_THAT(track({0}, {0, 0, 0, 0}, 4, Interpolation::Step, true).problem(),
                HasSubstr("the rotation of key 0 is zero"));
    EXPECT_EQ(track({0}, {0, 0, 0, 1}, 4, Interpolation::Step, true).problem(), "");
}

}  // namespace
}  // namespace glint
