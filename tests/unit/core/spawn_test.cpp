#include "glint/core/spawn.h"

#include <gtest/gtest.h>

#include <cmath>

#include "glint/scene/scene.h"

namespace glint {
namespace {

void expectNear(const Vec3& a, const Vec3& b, double eps) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

const Vec3 kDir{0.6, 0, -0.8};

TEST(Spawn, CourseScaleScenesUseTheCourseOffsetOfOneThousandth) {
    for (double extent : {1.0, 2.5, 40.0, 1e6}) EXPECT_EQ(sceneSpawnOffset(extent), 0.001);
    // Coordinates up to 65 (65 / 65536 < 0.001): the origin moves exactly 0.001 along dir.
    for (Vec3 p : {Vec3{0, 0, 0}, Vec3{1, 2, 3}, Vec3{-65, 30, 64.9}, Vec3{12.5, -7, 0}}) {
        SCOPED_TRACE(p.x);
        Ray r = spawnRay(p, kDir, sceneSpawnOffset(10));
        EXPECT_EQ(spawnOffset(p, 0.001), 0.001);
        expectNear(r.origin, p + kDir * 0.001, 1e-15);
        EXPECT_NEAR(length(r.origin - p), 0.001, 1e-13);  // rounding at |p| = 65
        EXPECT_EQ(r.dir, kDir);
        EXPECT_EQ(r.tMin, 0);
        EXPECT_EQ(r.tMax, kInfinity);
    }
}

TEST(Spawn, SmallScenesScaleTheAbsoluteOffsetDown) {
    EXPECT_DOUBLE_EQ(sceneSpawnOffset(0.5), 0.0005);
    EXPECT_DOUBLE_EQ(sceneSpawnOffset(0.001), 1e-6);
    EXPECT_EQ(sceneSpawnOffset(0), 0);
    // A scene 1000 times smaller moves the origin 1000 times less.
    Vec3 p{0.001, 0.002, 0.003};
    Ray r = spawnRay(p, kDir, sceneSpawnOffset(0.004));
    EXPECT_NEAR(length(r.origin - p), 4e-6, 1e-17);
}

TEST(Spawn, RelativePartTakesOverForLargeCoordinates) {
    // 2^-16 of the largest absolute coordinate, once that exceeds 0.001.
    EXPECT_DOUBLE_EQ(spawnOffset({65.536, 0, 0}, 0.001), 0.001);
    EXPECT_DOUBLE_EQ(spawnOffset({100, -3, 2}, 0.001), 100.0 / 65536);
    EXPECT_DOUBLE_EQ(spawnOffset({1, -6553.6, 2}, 0.001), 0.1);
    EXPECT_DOUBLE_EQ(spawnOffset({1, 2, -1e6}, 0.001), 1e6 / 65536);
    Vec3 p{3, -1000, 5};
    Ray r = spawnRay(p, kDir, 0.001);
    EXPECT_NEAR(length(r.origin - p), 1000.0 / 65536, 1e-12);
    // The moved origin is many float ulps away from the point (traversal is in float).
    float ulp = std::nextafter(1000.0f, 2000.0f) - 1000.0f;
    EXPECT_GT(length(r.origin - p), 100 * static_cast<double>(ulp));
    // In a small scene far from the origin the relative part wins too.
    EXPECT_DOUBLE_EQ(spawnOffset({0, 0, 500}, sceneSpawnOffset(0.01)), 500.0 / 65536);
}

TEST(Spawn, MaxDistanceBecomesTMaxShortenedByTheOffset) {
    Vec3 p{1, 2, 3}, light{4, 2, -1};  // distance 5
    Vec3 dir = normalize(light - p);
    Ray r = spawnRay(p, dir, 0.001, 5);
    EXPECT_DOUBLE_EQ(r.tMax, 5 - 0.001);
    EXPECT_EQ(r.tMin, 0);
    // The shadow ray ends at the light itself.
    expectNear(r.at(r.tMax), light, 1e-14);
    Ray far = spawnRay({0, 0, 1000}, {0, 0, 1}, 0.001, 20);
    EXPECT_DOUBLE_EQ(far.tMax, 20 - 1000.0 / 65536);
}

TEST(Spawn, SceneDerivesItsOffsetFromItsExtent) {
    Scene big;
    big.primitives.addTriangle({0, 0, 0}, {3, 0, 0}, {0, 2, 0}, nullptr, 0);
    big.prepare();
    EXPECT_EQ(big.spawnOffset(), 0.001);

    Scene tiny;  // largest extent 0.002 along y
    tiny.primitives.addTriangle({0, 0, 0}, {0.001, 0, 0}, {0, 0.002, 0}, nullptr, 0);
    tiny.prepare();
    EXPECT_NEAR(tiny.spawnOffset(), 2e-6, 1e-12);

    Scene empty;
    empty.prepare();
    EXPECT_EQ(empty.spawnOffset(), 0.001);
}

}  // namespace
}  // namespace glint
