#include "glint/math/transform.h"

#include <gtest/gtest.h>

#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

TEST(Transform, RightMultiplicationAppliesTheLastCommandFirst) {
    // translate then scale (as written in a scene file) scales the object first.
    Mat4 m = Mat4::translate(1, 0, 0) * Mat4::scale(2, 2, 2);
    auto t = Transform::fromMatrix(m);
    ASSERT_TRUE(t);
    expectNear(t->point({1, 0, 0}), {3, 0, 0});
    Mat4 other = Mat4::scale(2, 2, 2) * Mat4::translate(1, 0, 0);
    expectNear(Transform::fromMatrix(other)->point({1, 0, 0}), {4, 0, 0});
}

TEST(Transform, RotationIsInDegreesCounterClockwiseAsGlRotate) {
    auto t = Transform::fromMatrix(Mat4::rotate(0, 0, 1, 90));
    expectNear(t->point({1, 0, 0}), {0, 1, 0});
    // The axis need not be unit length.
    auto u = Transform::fromMatrix(Mat4::rotate(0, 0, 5, 90));
    expectNear(u->point({1, 0, 0}), {0, 1, 0});
}

TEST(Transform, VectorsIgnoreTranslation) {
    auto t = Transform::fromMatrix(Mat4::translate(5, 6, 7));
    expectNear(t->vector({1, 2, 3}), {1, 2, 3});
    expectNear(t->point({1, 2, 3}), {6, 8, 10});
}

TEST(Transform, NormalsUseTheInverseTranspose) {
    // A plane x + y = 0 with normal (1, 1, 0), scaled by 2 in x: the plane becomes x/2 + y = 0,
    // whose normal is (1, 2, 0) up to scale; transforming the normal as a vector would give
    // (2, 1, 0), which is wrong.
    auto t = Transform::fromMatrix(Mat4::scale(2, 1, 1));
    Vec3 n = normalize(t->normal({1, 1, 0}));
    expectNear(n, normalize(Vec3(1, 2, 0)));
    // It stays perpendicular to transformed tangent vectors.
    Vec3 tangent = t->vector({1, -1, 0});
    EXPECT_NEAR(dot(n, tangent), 0, 1e-12);
}

TEST(Transform, InverseUndoesTheTransform) {
    Mat4 m = Mat4::translate(1, -2, 3) * Mat4::rotate(1, 2, 3, 37) * Mat4::scale(0.5, 2, 3);
    auto t = Transform::fromMatrix(m);
    ASSERT_TRUE(t);
    Vec3 p{0.3, -0.7, 1.9};
    expectNear(t->inversePoint(t->point(p)), p);
    expectNear(t->inverse().point(t->point(p)), p);
    expectNear(t->inverseVector(t->vector(p)), p);
}

TEST(Transform, SingularMatricesAreRejected) {
    EXPECT_FALSE(Transform::fromMatrix(Mat4::scale(1, 0, 1)));
    EXPECT_TRUE(Transform::fromMatrix(Mat4::scale(1, 1e-6, 1)));
}

TEST(Transform, BallBoundsAreTightForEllipsoids) {
    // Unit sphere scaled to semi-axes (2, 1, 0.5), rotated 90 degrees about z: x <-> y.
    auto t = Transform::fromMatrix(Mat4::rotate(0, 0, 1, 90) * Mat4::scale(2, 1, 0.5));
    Bounds3f b = t->ballBounds({0, 0, 0}, 1);
    EXPECT_NEAR(b.hi.x, 1, 1e-6);
    EXPECT_NEAR(b.hi.y, 2, 1e-6);
    EXPECT_NEAR(b.hi.z, 0.5, 1e-6);
    EXPECT_NEAR(b.lo.y, -2, 1e-6);
}

}  // namespace
}  // namespace glint
