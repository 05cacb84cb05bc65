#include "glint/geometry/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "glint/geometry/primitives.h"
#include "glint/math/mat4.h"
#include "glint/math/rng.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

Shape makeShape(ShapeKind kind, const Mat4& objectFromCanonical, double k = 1,
                const Mat4& worldFromObject = Mat4{}) {
    auto t = Transform::fromMatrix(worldFromObject * objectFromCanonical);
    EXPECT_TRUE(t.has_value());
    return Shape{kind, k, t.value_or(Transform{})};
}
Shape box(const Vec3& a, const Vec3& b, const Mat4& m = Mat4{}) {
    return makeShape(ShapeKind::Box, boxPlacement(a, b), 1, m);
}
Shape cylinder(const Vec3& a, const Vec3& b, double r, const Mat4& m = Mat4{}) {
    return makeShape(ShapeKind::Cylinder, cylinderPlacement(a, b, r), 1, m);
}
Shape cone(const Vec3& a, double ra, const Vec3& b, double rb, const Mat4& m = Mat4{}) {
    double k = 1;
    Mat4 placement = conePlacement(a, ra, b, rb, k);
    return makeShape(ShapeKind::Cone, placement, k, m);
}
Shape disk(const Vec3& c, const Vec3& n, double r, const Mat4& m = Mat4{}) {
    return makeShape(ShapeKind::Disk, diskPlacement(c, n, r), 1, m);
}

Ray makeRay(const Vec3& origin, const Vec3& dir, double tMin = 0, double tMax = kInfinity) {
    return Ray{origin, normalize(dir), tMin, tMax};
}

/// The float search on one shape: the hit distance, or nothing.
std::optional<float> trace(const Shape& s, const Ray& ray) {
    float t;
    if (!intersectShape(s.search(), TraversalRay(ray), t)) return std::nullopt;
    return t;
}

/// The refined hit through Primitives (as the renderer gets it); fails the test on a miss.
SurfaceInteraction shade(const Shape& s, const Ray& ray) {
    Primitives prims;
    prims.addShape(s, 3);
    Hit hit;
    EXPECT_TRUE(prims.intersect(0, TraversalRay(ray), hit));
    SurfaceInteraction si = prims.interaction(ray, hit);
    EXPECT_EQ(si.material, 3u);
    EXPECT_NEAR(length(si.n), 1, 1e-12);
    EXPECT_EQ(si.n, si.ng);
    return si;
}

// ---- Box ----------------------------------------------------------------------------------

// Corners given in the "wrong" order: any two opposite corners will do.
const Shape kBox = box({1, 2, 3}, {-1, -2, -3});

TEST(Box, HitFromOutsideWithTheFaceNormal) {
    Ray ray = makeRay({0, 0, -10}, {0, 0, 1});
    EXPECT_FLOAT_EQ(trace(kBox, ray).value_or(-1), 7.0f);
    SurfaceInteraction si = shade(kBox, ray);
    expectNear(si.p, {0, 0, -3});
    expectNear(si.n, {0, 0, -1});
    expectNear(shade(kBox, makeRay({5, 0.5, 1}, {-1, 0, 0})).n, {1, 0, 0});
    expectNear(shade(kBox, makeRay({0.5, -9, 1}, {0, 1, 0})).n, {0, -1, 0});
}

TEST(Box, RayFromInsideFindsTheExitWithTheOutwardNormal) {
    Ray ray = makeRay({0.2, 0.3, 0.4}, {0, 1, 0});
    EXPECT_NEAR(trace(kBox, ray).value_or(-1), 1.7, 1e-6);
    SurfaceInteraction si = shade(kBox, ray);
    expectNear(si.p, {0.2, 2, 0.4});
    expectNear(si.n, {0, 1, 0});
}

TEST(Box, BehindOrBesideIsMissed) {
    EXPECT_FALSE(trace(kBox, makeRay({0, 0, 4}, {0, 0, 1})));
    EXPECT_FALSE(trace(kBox, makeRay({0, 0, -10}, {0, 0, -1})));
    EXPECT_FALSE(trace(kBox, makeRay({1.0001, 0, -10}, {0, 0, 1})));
    EXPECT_FALSE(trace(kBox, makeRay({0, 0, -10}, {0.2, 0.4, 1})));  // passes beside
}

TEST(Box, GrazingRaysInAFacePlaneAndThroughEdgesAndCornersHit) {
    // Along the face x = 1: the boundary counts as inside, as for a tangent sphere.
    EXPECT_FLOAT_EQ(trace(kBox, makeRay({1, 0, -10}, {0, 0, 1})).value_or(-1), 7.0f);
    EXPECT_FLOAT_EQ(trace(kBox, makeRay({0.9999, 0, -10}, {0, 0, 1})).value_or(-1), 7.0f);
    // Exactly through the corner (1, 2, 3) and along the edge x = 1, y = 2.
    auto corner = trace(kBox, makeRay({2, 3, 4}, {-1, -1, -1}));
    ASSERT_TRUE(corner);
    EXPECT_NEAR(*corner, std::sqrt(3.0), 1e-6);
    SurfaceInteraction si = shade(kBox, makeRay({2, 3, 4}, {-1, -1, -1}));
    expectNear(si.p, {1, 2, 3}, 1e-9);
    EXPECT_EQ(std::abs(si.n.x) + std::abs(si.n.y) + std::abs(si.n.z), 1);  // one face's normal
    EXPECT_FLOAT_EQ(trace(kBox, makeRay({1, 2, -10}, {0, 0, 1})).value_or(-1), 7.0f);
}

TEST(Box, TMinAndTMaxBoundTheAcceptedHit) {
    Vec3 o{0, 0, -10}, d{0, 0, 1};
    EXPECT_FALSE(trace(kBox, makeRay(o, d, 0, 6.9)));
    EXPECT_FLOAT_EQ(trace(kBox, makeRay(o, d, 7.5, kInfinity)).value_or(-1), 13.0f);  // exit
    EXPECT_FALSE(trace(kBox, makeRay(o, d, 13.5, kInfinity)));
}

// ---- Cylinder -----------------------------------------------------------------------------

const Shape kCylinder = cylinder({0, 0, 0}, {0, 0, 2}, 1);

TEST(Cylinder, SideHitFromOutsideAndFromInside) {
    Ray ray = makeRay({0, -5, 1}, {0, 1, 0});
    EXPECT_FLOAT_EQ(trace(kCylinder, ray).value_or(-1), 4.0f);
    SurfaceInteraction si = shade(kCylinder, ray);
    expectNear(si.p, {0, -1, 1});
    expectNear(si.n, {0, -1, 0});
    SurfaceInteraction in = shade(kCylinder, makeRay({0, 0, 1}, {1, 1, 0}));
    expectNear(in.p, {std::sqrt(0.5), std::sqrt(0.5), 1});
    expectNear(in.n, {std::sqrt(0.5), std::sqrt(0.5), 0});
}

TEST(Cylinder, RaysAlongTheAxisMeetTheCaps) {
    SurfaceInteraction bottom = shade(kCylinder, makeRay({0, 0, -5}, {0, 0, 1}));
    expectNear(bottom.p, {0, 0, 0});
    expectNear(bottom.n, {0, 0, -1});
    SurfaceInteraction top = shade(kCylinder, makeRay({0.3, 0.2, 1}, {0, 0, 1}));  // inside
    expectNear(top.p, {0.3, 0.2, 2});
    expectNear(top.n, {0, 0, 1});
    EXPECT_FALSE(trace(kCylinder, makeRay({0, 0, 2.5}, {0, 0, 1})));  // behind
    EXPECT_FALSE(trace(kCylinder, makeRay({1.01, 0, -5}, {0, 0, 1})));
}

TEST(Cylinder, TangentRimAndCapEdgeRaysHit) {
    // Tangent to the side at (1, 0, 1).
    auto tangent = trace(kCylinder, makeRay({1, -5, 1}, {0, 1, 0}));
    ASSERT_TRUE(tangent);
    EXPECT_NEAR(*tangent, 5, 1e-5);
    // Along a line of the side surface: enters through the bottom rim.
    EXPECT_FLOAT_EQ(trace(kCylinder, makeRay({1, 0, -5}, {0, 0, 1})).value_or(-1), 5.0f);
    // Exactly at the top rim (1, 0, 2), diagonally from outside.
    SurfaceInteraction rim = shade(kCylinder, makeRay({4, 0, 5}, {-1, 0, -1}));
    expectNear(rim.p, {1, 0, 2}, 1e-9);
    EXPECT_TRUE(rim.n == Vec3(1, 0, 0) || rim.n == Vec3(0, 0, 1));
    // Just inside the rim from above hits the cap; just outside misses altogether.
    expectNear(shade(kCylinder, makeRay({0.9999, 0, 5}, {0, 0, -1})).n, {0, 0, 1});
    EXPECT_FALSE(trace(kCylinder, makeRay({1.0001, 0, 5}, {0, 0, -1})));
    // Parallel to the caps, just above the top: a miss.
    EXPECT_FALSE(trace(kCylinder, makeRay({0, -5, 2.0001}, {0, 1, 0})));
}

TEST(Cylinder, SlantedAxisUnderNonUniformScaleAndRotationHasTheInverseTransposeNormal) {
    // Object space: the unit cylinder from z = 0 to z = 1. World: stretched 2x along x, then
    // rotated 30 degrees about z. On the side at angle 60 degrees the object normal is
    // (cos 60, sin 60, 0); by hand, M^-T = R S^-1, so the world normal is
    // R (cos 60 / 2, sin 60, 0), normalised.
    Mat4 m = Mat4::rotate(0, 0, 1, 30) * Mat4::scale(2, 1, 1);
    Shape s = cylinder({0, 0, 0}, {0, 0, 1}, 1, m);
    const double pi = std::acos(-1.0), a = pi / 3, r = pi / 6;
    Vec3 local(std::cos(a), std::sin(a), 0.5);
    Vec3 p(std::cos(r) * 2 * local.x - std::sin(r) * local.y,
           std::sin(r) * 2 * local.x + std::cos(r) * local.y, 0.5);
    Vec3 nS(std::cos(a) / 2, std::sin(a), 0);
    Vec3 expected = normalize(
        Vec3(std::cos(r) * nS.x - std::sin(r) * nS.y, std::sin(r) * nS.x + std::cos(r) * nS.y, 0));
    // A ray coming in along the normal meets the convex shape first at p.
    SurfaceInteraction si = shade(s, makeRay(p + expected * 10.0, -expected));
    expectNear(si.p, p, 1e-9);
    expectNear(si.n, expected, 1e-9);
}

// ---- Cone ---------------------------------------------------------------------------------

// Pointed: radius 1 at z = 0, apex at z = 2 (radius at height z: 1 - z / 2).
const Shape kCone = cone({0, 0, 0}, 1, {0, 0, 2}, 0);

TEST(Cone, SideHitWithTheSlantedOutwardNormal) {
    Ray ray = makeRay({0, -5, 0.5}, {0, 1, 0});
    EXPECT_FLOAT_EQ(trace(kCone, ray).value_or(-1), 4.25f);
    SurfaceInteraction si = shade(kCone, ray);
    expectNear(si.p, {0, -0.75, 0.5});
    // By hand: the gradient of sqrt(x^2 + y^2) - (1 - z / 2) is (x / r, y / r, 1 / 2).
    expectNear(si.n, normalize(Vec3(0, -1, 0.5)));
}

TEST(Cone, FromInsideTheBaseAndTheApex) {
    SurfaceInteraction in = shade(kCone, makeRay({0, 0, 0.5}, {1, 0, 0}));
    expectNear(in.p, {0.75, 0, 0.5});
    expectNear(in.n, normalize(Vec3(1, 0, 0.5)));
    SurfaceInteraction base = shade(kCone, makeRay({0.2, 0, -3}, {0, 0, 1}));
    expectNear(base.p, {0.2, 0, 0});
    expectNear(base.n, {0, 0, -1});
    // Along the axis from above: the apex is the first point, a single point.
    auto apex = trace(kCone, makeRay({0, 0, 5}, {0, 0, -1}));
    ASSERT_TRUE(apex);
    EXPECT_NEAR(*apex, 3, 1e-5);
    // From inside, straight up: out through the apex.
    EXPECT_NEAR(trace(kCone, makeRay({0, 0, 1}, {0, 0, 1})).value_or(-1), 1, 1e-5);
}

TEST(Cone, TangentRimAndBehind) {
    // Tangent to the side where the radius is 0.5 (z = 1).
    auto tangent = trace(kCone, makeRay({0.5, -5, 1}, {0, 1, 0}));
    ASSERT_TRUE(tangent);
    EXPECT_NEAR(*tangent, 5, 1e-4);
    EXPECT_FALSE(trace(kCone, makeRay({0.5001, -5, 1}, {0, 1, 0})));
    // The base rim (1, 0, 0) from below and outside.
    SurfaceInteraction rim = shade(kCone, makeRay({4, 0, -3}, {-1, 0, 1}));
    expectNear(rim.p, {1, 0, 0}, 1e-9);
    EXPECT_FALSE(trace(kCone, makeRay({0, 0, 2.5}, {0, 0, 1})));
    EXPECT_FALSE(trace(kCone, makeRay({0, -5, 0.5}, {0, -1, 0})));
}

TEST(Cone, FrustumHasATopCapAndEndsInEitherOrder) {
    // Radius 1 at z = 0, 0.5 at z = 2, given wide end first and narrow end first.
    for (const Shape& s :
         {cone({0, 0, 0}, 1, {0, 0, 2}, 0.5), cone({0, 0, 2}, 0.5, {0, 0, 0}, 1)}) {
        EXPECT_DOUBLE_EQ(s.k, 0.5);
        SurfaceInteraction top = shade(s, makeRay({0.4, 0, 5}, {0, 0, -1}));
        expectNear(top.p, {0.4, 0, 2});
        expectNear(top.n, {0, 0, 1});
        // Just outside the cap: down past it onto the side, where the radius is 0.55.
        EXPECT_NEAR(trace(s, makeRay({0.55, 0, 5}, {0, 0, -1})).value_or(-1), 3.2, 1e-5);
        SurfaceInteraction side = shade(s, makeRay({-5, 0, 1}, {1, 0, 0}));
        expectNear(side.p, {-0.75, 0, 1});
        expectNear(side.n, normalize(Vec3(-1, 0, 0.25)));
    }
}

TEST(Cone, SideNormalUnderNonUniformScaleAndRotation) {
    // Object: radius 1 at z = 0, apex at z = 1, so the side normal at angle phi is
    // (cos phi, sin phi, 1) / sqrt(2). World: scale (1, 3, 0.5), then rotate 90 degrees about
    // x: M^-T = R S^-1, normal R (cos phi, sin phi / 3, 2) normalised, with R (x, y, z) =
    // (x, -z, y).
    Mat4 m = Mat4::rotate(1, 0, 0, 90) * Mat4::scale(1, 3, 0.5);
    Shape s = cone({0, 0, 0}, 1, {0, 0, 1}, 0, m);
    const double phi = 2.0;
    Vec3 local(0.6 * std::cos(phi), 0.6 * std::sin(phi), 0.4);  // radius 1 - 0.4
    Vec3 scaled(local.x, 3 * local.y, 0.5 * local.z);
    Vec3 p(scaled.x, -scaled.z, scaled.y);
    Vec3 nS(std::cos(phi), std::sin(phi) / 3, 2);
    Vec3 expected = normalize(Vec3(nS.x, -nS.z, nS.y));
    SurfaceInteraction si = shade(s, makeRay(p + expected * 7.0, -expected));
    expectNear(si.p, p, 1e-9);
    expectNear(si.n, expected, 1e-9);
}

// ---- Disk ---------------------------------------------------------------------------------

const Shape kDisk = disk({0, 0, 1}, {0, 0, 3}, 2);

TEST(Disk, BothSidesHitWithTheGivenNormalNeverFlipped) {
    SurfaceInteraction above = shade(kDisk, makeRay({0.5, 0.5, 6}, {0, 0, -1}));
    expectNear(above.p, {0.5, 0.5, 1});
    expectNear(above.n, {0, 0, 1});
    SurfaceInteraction below = shade(kDisk, makeRay({0.5, 0.5, -6}, {0, 0, 1}));
    expectNear(below.n, {0, 0, 1});
}

TEST(Disk, RimParallelAndBehind) {
    EXPECT_FLOAT_EQ(trace(kDisk, makeRay({2, 0, 6}, {0, 0, -1})).value_or(-1), 5.0f);  // rim
    EXPECT_FALSE(trace(kDisk, makeRay({2.0001, 0, 6}, {0, 0, -1})));
    EXPECT_FALSE(trace(kDisk, makeRay({-5, 0, 1}, {1, 0, 0})));  // in its plane
    EXPECT_FALSE(trace(kDisk, makeRay({0, 0, 0}, {0, 0, -1})));  // behind
}

TEST(Disk, TiltedNormalUnderNonUniformScale) {
    // Normal (1, 1, 0) in object space, scaled (2, 1, 1) in world: by hand the world normal
    // is S^-1 (1, 1, 0) = (0.5, 1, 0), normalised.
    Shape s = disk({0, 0, 0}, {1, 1, 0}, 1, Mat4::scale(2, 1, 1));
    Vec3 expected = normalize(Vec3(0.5, 1, 0));
    SurfaceInteraction si = shade(s, makeRay(expected * 4.0, -expected));
    expectNear(si.p, {0, 0, 0}, 1e-12);
    expectNear(si.n, expected, 1e-12);
}

// ---- Bounds and precision -----------------------------------------------------------------

TEST(Shapes, BoundsHoldTheShapeTightly) {
    auto expectBounds = [](const Shape& s, const Vec3& lo, const Vec3& hi) {
        Bounds3f b = s.bounds();
        for (int a = 0; a < 3; ++a) {
            EXPECT_LE(b.lo[a], lo[a]);
            EXPECT_GE(b.hi[a], hi[a]);
            EXPECT_NEAR(b.lo[a], lo[a], 1e-3);
            EXPECT_NEAR(b.hi[a], hi[a], 1e-3);
        }
    };
    expectBounds(kBox, {-1, -2, -3}, {1, 2, 3});
    expectBounds(kCylinder, {-1, -1, 0}, {1, 1, 2});
    expectBounds(kCone, {-1, -1, 0}, {1, 1, 2});
    expectBounds(kDisk, {-2, -2, 1}, {2, 2, 1});
    // A disk tilted 45 degrees about y: an ellipse of half extents (sqrt(.5), 1, sqrt(.5)).
    double h = std::sqrt(0.5);
    expectBounds(disk({0, 0, 0}, {1, 0, 1}, 1), {-h, -1, -h}, {h, 1, h});
}

TEST(Shapes, RefinedHitsLieOnTheSurfaceForRandomRaysUnderRandomTransforms) {
    Rng rng(42);
    auto uni = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform(); };
    int hits = 0;
    for (int i = 0; i < 400; ++i) {
        Mat4 m = Mat4::translate(uni(-5, 5), uni(-5, 5), uni(-5, 5)) *
                 Mat4::rotate(uni(-1, 1), uni(-1, 1), 1, uni(0, 360)) *
                 Mat4::scale(uni(0.2, 3), uni(0.2, 3), uni(0.2, 3));
        Shape shapes[] = {box({-1, -1, -1}, {1, 0.5, 2}, m), cylinder({0, 0, 0}, {1, 2, 0}, 0.7, m),
                          cone({0, 0, 0}, 1, {0, 1, 1}, 0.3, m), disk({0, 0, 0}, {0, 1, 1}, 1, m)};
        for (const Shape& s : shapes) {
            Vec3 target = s.worldFromCanonical.point({uni(-0.5, 0.5), uni(-0.5, 0.5), 0.5});
            Vec3 origin(uni(-20, 20), uni(-20, 20), uni(-20, 20));
            Ray ray = makeRay(origin, target - origin);
            Primitives prims;
            prims.addShape(s, 0);
            Hit hit;
            if (!prims.intersect(0, TraversalRay(ray), hit)) continue;
            ++hits;
            SurfaceInteraction si = prims.interaction(ray, hit);
            double tRefined = dot(si.p - ray.origin, ray.dir);
            EXPECT_NEAR(tRefined, hit.t, 1e-4 * std::max(1.0, tRefined));
            // On the canonical surface: some face, side or cap equation holds.
            Vec3 c = s.worldFromCanonical.inversePoint(si.p);
            double rho = std::hypot(c.x, c.y), residual = 0;
            switch (s.kind) {
                case ShapeKind::Box:
                    residual = std::abs(maxComponent(abs(c)) - 1);
                    break;
                case ShapeKind::Cylinder:
                    residual = std::min({std::abs(rho - 1), std::abs(c.z), std::abs(c.z - 1)});
                    break;
                case ShapeKind::Cone:
                    residual = std::min(
                        {std::abs(rho - (1 - (1 - s.k) * c.z)), std::abs(c.z), std::abs(c.z - 1)});
                    break;
                default:
                    residual = std::abs(c.z);
            }
            EXPECT_LT(residual, 1e-9) << static_cast<int>(s.kind);
            EXPECT_NEAR(length(si.n), 1, 1e-12);
        }
    }
    EXPECT_GT(hits, 1000);
}

TEST(Shapes, SmallDistantCylinderIsHitAccurately) {
    // Radius 0.01 at distance 1000: the side quadratic must not cancel in float.
    Shape s = cylinder({0, -1, 1000}, {0, 1, 1000}, 0.01);
    Ray ray = makeRay({0, 0, 0}, {0.005, 0, 1000});
    double along = dot(Vec3(0, 0, 1000), ray.dir);
    double miss = length(cross(Vec3(0, 0, 1000), ray.dir));
    double expected = along - std::sqrt(0.01 * 0.01 - miss * miss);
    auto t = trace(s, ray);
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, expected, 1e-3);
}

}  // namespace
}  // namespace glint
