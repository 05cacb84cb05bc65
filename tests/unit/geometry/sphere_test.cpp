#include "glint/geometry/sphere.h"

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

Sphere makeSphere(const Vec3& center, double radius, const Mat4& worldFromObject = Mat4{}) {
    auto t = Transform::fromMatrix(worldFromObject);
    EXPECT_TRUE(t.has_value());
    return Sphere{center, radius, t.value_or(Transform{})};
}

Ray makeRay(const Vec3& origin, const Vec3& dir, double tMin = 0, double tMax = kInfinity) {
    return Ray{origin, normalize(dir), tMin, tMax};
}

/// The float search on one sphere: the hit distance, or nothing.
std::optional<float> trace(const Sphere& s, const Ray& ray) {
    float t;
    if (!intersectSphere(sphereSearch(s), TraversalRay(ray), t)) return std::nullopt;
    return t;
}

// Unit sphere centred 5 units down the z axis.
const Sphere kUnit = makeSphere({0, 0, 5}, 1);

TEST(Sphere, TwoRootsTheNearerIsChosen) {
    auto t = trace(kUnit, makeRay({0, 0, 0}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 4.0f);

    // The same through Primitives, which also sets the id and refines the hit in double.
    Primitives prims;
    prims.addSphere(kUnit, 7);
    Ray ray = makeRay({0, 0, 0}, {0, 0, 1});
    Hit hit;
    hit.primId = 99;
    ASSERT_TRUE(prims.intersect(0, TraversalRay(ray), hit));
    EXPECT_EQ(hit.primId, 0u);
    SurfaceInteraction si = prims.interaction(ray, hit);
    expectNear(si.p, {0, 0, 4});
    expectNear(si.n, {0, 0, -1});
    expectNear(si.ng, {0, 0, -1});
    EXPECT_EQ(si.material, 7u);
}

TEST(Sphere, TangentRayTouchesAtOnePoint) {
    auto t = trace(kUnit, makeRay({1, 0, 0}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 5.0f);
}

TEST(Sphere, GrazingRaysJustInsideHitAndJustOutsideMiss) {
    EXPECT_FALSE(trace(kUnit, makeRay({1.0001, 0, 0}, {0, 0, 1})));
    EXPECT_FALSE(trace(kUnit, makeRay({0, -1.0001, 0}, {0, 0, 1})));
    auto t = trace(kUnit, makeRay({0.9999, 0, 0}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 5 - std::sqrt(1 - 0.9999 * 0.9999), 1e-4);
}

TEST(Sphere, OriginInsideHitsTheFarRoot) {
    auto t = trace(kUnit, makeRay({0, 0, 5}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_FLOAT_EQ(*t, 1.0f);
    auto off = trace(kUnit, makeRay({0.5, 0, 5}, {0, 0, -1}));
    ASSERT_TRUE(off);
    EXPECT_NEAR(*off, std::sqrt(0.75), 1e-6);
}

TEST(Sphere, SphereBehindTheOriginIsMissed) {
    EXPECT_FALSE(trace(kUnit, makeRay({0, 0, 10}, {0, 0, 1})));
    EXPECT_FALSE(trace(kUnit, makeRay({0, 0, 6.5}, {0, 0.1, 1})));
}

TEST(Sphere, RayPassingBesideMisses) {
    // Distance from the centre to the ray is 5 / sqrt(2) > 1.
    EXPECT_FALSE(trace(kUnit, makeRay({0, 0, 0}, {0, 1, 1})));
    EXPECT_FALSE(trace(kUnit, makeRay({0, 0, 0}, {1, 0, 0})));
}

TEST(Sphere, TMinAndTMaxBoundTheAcceptedRoots) {
    Vec3 o{0, 0, 0}, d{0, 0, 1};
    EXPECT_FALSE(trace(kUnit, makeRay(o, d, 0, 3.9)));
    EXPECT_FLOAT_EQ(trace(kUnit, makeRay(o, d, 0, 4.5)).value_or(-1), 4.0f);
    // tMin past the near root: the far root is taken.
    EXPECT_FLOAT_EQ(trace(kUnit, makeRay(o, d, 4.5, kInfinity)).value_or(-1), 6.0f);
    EXPECT_FALSE(trace(kUnit, makeRay(o, d, 4.5, 5.5)));
    EXPECT_FALSE(trace(kUnit, makeRay(o, d, 6.5, kInfinity)));

    // A closer hit already found is kept.
    Primitives prims;
    prims.addSphere(kUnit, 0);
    Hit hit{3, 7};
    EXPECT_FALSE(prims.intersect(0, TraversalRay(makeRay(o, d)), hit));
    EXPECT_EQ(hit.t, 3.0f);
    EXPECT_EQ(hit.primId, 7u);
}

TEST(Sphere, SmallDistantSphereIsHitAccurately) {
    // Radius 0.01 at distance 1000: the textbook quadratic loses all digits in float here.
    Sphere s = makeSphere({0, 0, 1000}, 0.01);
    Ray ray = makeRay({0, 0, 0}, {0.005, 0, 1000});
    // Closest approach and hit distance by hand.
    double along = dot(Vec3(0, 0, 1000), ray.dir);
    double miss = length(cross(Vec3(0, 0, 1000), ray.dir));  // no cancellation
    double expected = along - std::sqrt(0.01 * 0.01 - miss * miss);
    auto t = trace(s, ray);
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, expected, 1e-3);

    Primitives prims;
    prims.addSphere(s, 0);
    Hit hit;
    ASSERT_TRUE(prims.intersect(0, TraversalRay(ray), hit));
    SurfaceInteraction si = prims.interaction(ray, hit);
    EXPECT_NEAR(length(si.p - s.center), 0.01, 1e-10);
    expectNear(si.p, ray.at(expected), 1e-9);
}

TEST(Ellipsoid, AxisAlignedScaleGivesTheSemiAxesAsHitDistances) {
    Primitives prims;
    prims.addSphere(makeSphere({0, 0, 0}, 1, Mat4::scale(2, 0.5, 1)), 0);
    struct Case {
        Vec3 origin, dir, point, normal;
    } cases[] = {{{-10, 0, 0}, {1, 0, 0}, {-2, 0, 0}, {-1, 0, 0}},
                 {{0, -10, 0}, {0, 1, 0}, {0, -0.5, 0}, {0, -1, 0}},
                 {{0, 0, 10}, {0, 0, -1}, {0, 0, 1}, {0, 0, 1}}};
    for (const Case& c : cases) {
        Ray ray = makeRay(c.origin, c.dir);
        Hit hit;
        ASSERT_TRUE(prims.intersect(0, TraversalRay(ray), hit));
        EXPECT_FLOAT_EQ(hit.t, static_cast<float>(length(c.point - c.origin)));
        SurfaceInteraction si = prims.interaction(ray, hit);
        expectNear(si.p, c.point);
        expectNear(si.ng, c.normal);
    }
}

TEST(Ellipsoid, RotatedEllipsoidHasItsLongAxisTurned) {
    // Semi-axis 2 along x, turned 90 degrees about z: it now lies along y.
    Sphere s = makeSphere({0, 0, 0}, 1, Mat4::rotate(0, 0, 1, 90) * Mat4::scale(2, 0.5, 1));
    EXPECT_FLOAT_EQ(trace(s, makeRay({0, -10, 0}, {0, 1, 0})).value_or(-1), 8.0f);
    EXPECT_FLOAT_EQ(trace(s, makeRay({-10, 0, 0}, {1, 0, 0})).value_or(-1), 9.5f);
    // Unrotated, x = 1.9 would be inside the long axis; turned, the x semi-axis is 0.5.
    EXPECT_FALSE(trace(s, makeRay({1.9, -10, 0}, {0, 1, 0})));
    EXPECT_TRUE(trace(s, makeRay({-10, 1.9, 0}, {1, 0, 0})));
}

// An ellipsoid M = T R S applied to a sphere with its own object-space centre and radius, and
// an independent solution: object point q = S^-1 R^T (x - T), surface |q - c| = r, world
// normal R S^-1 (q - c) (the inverse transpose of R S).
struct AnalyticEllipsoid {
    Vec3 translation{1, -2, 0.5}, scale{2.5, 0.4, 1.2}, axis{1, 2, -1};
    double degrees = 37;
    Vec3 center{0.3, -0.2, 0.1};
    double radius = 1.5;

    Mat4 rotation() const { return Mat4::rotate(axis.x, axis.y, axis.z, degrees); }
    Mat4 matrix() const {
        return Mat4::translate(translation.x, translation.y, translation.z) * rotation() *
               Mat4::scale(scale.x, scale.y, scale.z);
    }
    static Vec3 apply3(const Mat4& m, const Vec3& v) {
        return {m.m[0][0] * v.x + m.m[0][1] * v.y + m.m[0][2] * v.z,
                m.m[1][0] * v.x + m.m[1][1] * v.y + m.m[1][2] * v.z,
                m.m[2][0] * v.x + m.m[2][1] * v.y + m.m[2][2] * v.z};
    }
    Vec3 objectPoint(const Vec3& x) const {
        return apply3(transpose(rotation()), x - translation) / scale;
    }
    Vec3 objectVector(const Vec3& v) const { return apply3(transpose(rotation()), v) / scale; }
    Vec3 worldNormal(const Vec3& x) const {
        return normalize(apply3(rotation(), (objectPoint(x) - center) / scale));
    }
    /// Hit distances of the world ray by the textbook quadratic in double; false on a miss.
    bool roots(const Ray& ray, double& t0, double& t1) const {
        Vec3 o = objectPoint(ray.origin) - center, d = objectVector(ray.dir);
        double a = dot(d, d), b = 2 * dot(o, d), c = dot(o, o) - radius * radius;
        double disc = b * b - 4 * a * c;
        if (disc < 0) return false;
        t0 = (-b - std::sqrt(disc)) / (2 * a);
        t1 = (-b + std::sqrt(disc)) / (2 * a);
        return true;
    }
    /// Closest approach of the object-space ray line to the centre, over the radius.
    double closestApproach(const Ray& ray) const {
        Vec3 o = objectPoint(ray.origin) - center, d = objectVector(ray.dir);
        return length(o - d * (dot(o, d) / dot(d, d))) / radius;
    }
};

TEST(Ellipsoid, HitDistancePointAndNormalMatchTheAnalyticSolution) {
    AnalyticEllipsoid e;
    Sphere s = makeSphere(e.center, e.radius, e.matrix());
    Primitives prims;
    prims.addSphere(s, 0);
    Rng rng(12345);
    auto uni = [&](double lo, double hi) { return lo + (hi - lo) * double(rng.uniform()); };
    int hits = 0, misses = 0;
    for (int i = 0; i < 500; ++i) {
        Vec3 origin{uni(-8, 8), uni(-8, 8), uni(-8, 8)};
        Vec3 target = e.translation + Vec3{uni(-4, 4), uni(-4, 4), uni(-4, 4)};
        if (i % 10 == 0) origin = e.translation + Vec3{uni(-0.1, 0.1), 0, 0};  // inside
        Ray ray = makeRay(origin, target - origin);
        SCOPED_TRACE(i);
        double t0 = 0, t1 = 0;
        bool expectHit = e.roots(ray, t0, t1) && t1 > 0;
        Hit hit;
        bool found = prims.intersect(0, TraversalRay(ray), hit);
        // Skip rays within float noise of tangency, where either answer is right.
        if (std::abs(e.closestApproach(ray) - 1) < 1e-4) continue;
        ASSERT_EQ(found, expectHit);
        if (!found) {
            ++misses;
            continue;
        }
        ++hits;
        double t = t0 > 0 ? t0 : t1;
        EXPECT_NEAR(hit.t, t, 1e-5 * t);
        SurfaceInteraction si = prims.interaction(ray, hit);
        expectNear(si.p, ray.at(t), 1e-11);
        EXPECT_NEAR(length(e.objectPoint(si.p) - e.center), e.radius, 1e-12);
        expectNear(si.ng, e.worldNormal(si.p), 1e-12);
        expectNear(si.n, si.ng, 0);
    }
    EXPECT_GT(hits, 100);
    EXPECT_GT(misses, 20);
}

TEST(Ellipsoid, NormalIsNotTheTransformedObjectNormal) {
    // At the object point (1, 1, 0) / sqrt(2) of a unit sphere scaled by (4, 1, 1), the normal
    // is along (1/4, 1, 0), not along the scaled (4, 1, 0).
    Primitives prims;
    prims.addSphere(makeSphere({0, 0, 0}, 1, Mat4::scale(4, 1, 1)), 0);
    Vec3 p{4 / std::sqrt(2.0), 1 / std::sqrt(2.0), 0};
    // Come in along the true normal, so that p is the first hit.
    Ray ray = makeRay(p + Vec3{1, 4, 0}, {-1, -4, 0});
    Hit hit;
    ASSERT_TRUE(prims.intersect(0, TraversalRay(ray), hit));
    SurfaceInteraction si = prims.interaction(ray, hit);
    expectNear(si.p, p, 1e-12);
    expectNear(si.ng, normalize(Vec3{0.25, 1, 0}), 1e-12);
}

}  // namespace
}  // namespace glint
