#include "glint/geometry/triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "glint/geometry/primitives.h"
#include "glint/math/rng.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;

Ray makeRay(const Vec3& origin, const Vec3& dir, double tMin = 0, double tMax = kInfinity) {
    return Ray{origin, normalize(dir), tMin, tMax};
}

std::optional<float> trace(const Triangle& tri, const Ray& ray) {
    float t;
    if (!intersectTriangle(tri, TraversalRay(ray), t)) return std::nullopt;
    return t;
}

// The right triangle A = 0, B = x, C = y in the plane z = 0, normal +z.
const Triangle kRight = Triangle::fromVertices({0, 0, 0}, {1, 0, 0}, {0, 1, 0});

/// A ray straight down onto (x, y) of the plane z = 0 from height 1.
Ray down(double x, double y) { return makeRay({x, y, 1}, {0, 0, -1}); }

TEST(Triangle, RayThroughTheInteriorHits) {
    auto t = trace(kRight, down(0.25, 0.25));
    ASSERT_TRUE(t);
    EXPECT_EQ(*t, 1.0f);
    TriangleHit th = refineTriangleHit(kRight, down(0.25, 0.25), *t);
    EXPECT_DOUBLE_EQ(th.t, 1);
    EXPECT_DOUBLE_EQ(th.b1, 0.25);
    EXPECT_DOUBLE_EQ(th.b2, 0.25);
}

TEST(Triangle, PointsExactlyOnEdgesCountAsHits) {
    EXPECT_TRUE(trace(kRight, down(0.5, 0)));    // edge AB
    EXPECT_TRUE(trace(kRight, down(0, 0.5)));    // edge AC
    EXPECT_TRUE(trace(kRight, down(0.5, 0.5)));  // edge BC (u + v = 1)
    EXPECT_TRUE(trace(kRight, down(0.75, 0.25)));
}

TEST(Triangle, PointsExactlyOnVerticesCountAsHits) {
    EXPECT_TRUE(trace(kRight, down(0, 0)));
    EXPECT_TRUE(trace(kRight, down(1, 0)));
    EXPECT_TRUE(trace(kRight, down(0, 1)));
}

TEST(Triangle, PointsJustOutsideMiss) {
    EXPECT_FALSE(trace(kRight, down(0.5, -1e-4)));
    EXPECT_FALSE(trace(kRight, down(-1e-4, 0.5)));
    EXPECT_FALSE(trace(kRight, down(0.5 + 1e-4, 0.5)));
    EXPECT_FALSE(trace(kRight, down(1 + 1e-4, 0)));
    EXPECT_FALSE(trace(kRight, down(0, 1 + 1e-4)));
    EXPECT_FALSE(trace(kRight, down(-1e-4, -1e-4)));
}

TEST(Triangle, RaysParallelToOrInThePlaneMiss) {
    EXPECT_FALSE(trace(kRight, makeRay({0.25, 0.25, 1}, {1, 0, 0})));
    EXPECT_FALSE(trace(kRight, makeRay({-1, 0.25, 0}, {1, 0, 0})));  // in the plane, across
    EXPECT_FALSE(trace(kRight, makeRay({0.1, 0.1, 0}, {1, 1, 0})));  // in the plane, inside
    EXPECT_FALSE(trace(kRight, makeRay({-1, -1, 0}, {1, 1.5, 0})));  // in the plane, oblique
}

/// Counts hits on `tri` by 1000 random rays through points `on(s)`, s in [0, 1].
template <typename F>
int hitsThrough(const Triangle& tri, F on, std::string* first) {
    Rng rng(7);
    auto uni = [&](double lo, double hi) { return lo + (hi - lo) * double(rng.uniform()); };
    int count = 0;
    for (int i = 0; i < 1000; ++i) {
        Vec3 dir{uni(-1, 1), uni(-1, 1), uni(-1, 1)};
        if (length(dir) < 0.1) continue;
        Vec3 p = on(uni(0, 1));
        Ray ray = makeRay(p - normalize(dir) * 3.0, dir);
        auto t = trace(tri, ray);
        if (t && count++ == 0)
            *first = "through (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
                     std::to_string(p.z) + ") at distance 3, reported t = " + std::to_string(*t);
    }
    return count;
}

TEST(Triangle, TrianglesWithRepeatedVerticesNeverHit) {
    const Triangle repeated = Triangle::fromVertices({1, 2, 3}, {1, 2, 3}, {4, 0, 1});
    const Triangle point = Triangle::fromVertices({1, 1, 1}, {1, 1, 1}, {1, 1, 1});
    std::string first;
    EXPECT_EQ(hitsThrough(
                  repeated,
                  [](double s) {
                      return Vec3{1, 2, 3} + Vec3{3, -2, -2} * s;
                  },
                  &first),
              0)
        << first;
    EXPECT_EQ(hitsThrough(
                  point,
                  [](double) {
                      return Vec3{1, 1, 1};
                  },
                  &first),
              0)
        << first;
}

TEST(Triangle, CollinearTrianglesAreDetectedAsDegenerate) {
    // C - A = 2 (B - A) exactly (in float): no normal to shade with.
    const Triangle collinear = Triangle::fromVertices({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
    EXPECT_TRUE(collinear.degenerate());
    EXPECT_EQ(collinear.normalDirection(), Vec3(0));
    // Nearly collinear but not exactly: a valid sliver.
    EXPECT_FALSE(Triangle::fromVertices({0, 0, 0}, {1, 1, 1}, {2, 2, 2.001}).degenerate());
    EXPECT_FALSE(kRight.degenerate());
}

TEST(Triangle, PrimitivesDropDegenerateTrianglesSoTheyNeverHit) {
    // The float determinant of a collinear triangle can round to +-1e-7 instead of 0, so the
    // guarantee lives where triangles are stored: Primitives never keeps them.
    Primitives prims;
    EXPECT_FALSE(prims.addTriangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, nullptr, 0));
    EXPECT_FALSE(prims.addTriangle({0, 0, 0}, {0, 0, 0}, {1, 2, 3}, nullptr, 0));
    EXPECT_TRUE(prims.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, nullptr, 0));
    EXPECT_EQ(prims.triangleCount(), 1u);
}

TEST(Triangle, BackFacesAreHit) {
    auto t = trace(kRight, makeRay({0.25, 0.25, -2}, {0, 0, 1}));
    ASSERT_TRUE(t);
    EXPECT_EQ(*t, 2.0f);
}

TEST(Triangle, TMinAndTMaxBoundTheHit) {
    EXPECT_FALSE(trace(kRight, makeRay({0.25, 0.25, 1}, {0, 0, -1}, 0, 0.5)));
    EXPECT_FALSE(trace(kRight, makeRay({0.25, 0.25, 1}, {0, 0, -1}, 1.5, kInfinity)));
    EXPECT_TRUE(trace(kRight, makeRay({0.25, 0.25, 1}, {0, 0, -1}, 0.5, 1.5)));
    // Behind the origin.
    EXPECT_FALSE(trace(kRight, makeRay({0.25, 0.25, 1}, {0, 0, 1})));
    // A closer hit already found is kept.
    Primitives prims;
    prims.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, nullptr, 0);
    Hit hit{0.5f, 9};
    EXPECT_FALSE(prims.intersect(0, TraversalRay(down(0.25, 0.25)), hit));
    EXPECT_EQ(hit.t, 0.5f);
    EXPECT_EQ(hit.primId, 9u);
}

TEST(Triangle, HitsAtTheSameDistanceGoToTheLowerPrimitiveId) {
    // Two copies of one triangle: whichever is tested first, id 0 wins.
    Primitives prims;
    prims.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, nullptr, 0);
    prims.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, nullptr, 0);
    TraversalRay ray(down(0.25, 0.25));
    Hit first, second;
    EXPECT_TRUE(prims.intersect(1, ray, first));
    EXPECT_TRUE(prims.intersect(0, ray, first));
    EXPECT_EQ(first.primId, 0u);
    EXPECT_TRUE(prims.intersect(0, ray, second));
    EXPECT_FALSE(prims.intersect(1, ray, second));
    EXPECT_EQ(second.primId, 0u);
    EXPECT_EQ(first.t, second.t);
}

// The triangle A = (1,0,0), B = (0,2,0), C = (0,0,3) in the plane x + y/2 + z/3 = 1.
// (B - A) x (C - A) = (-1,2,0) x (-1,0,3) = (6, 3, 2), of length 7.
// The ray from the origin along (1,1,1) meets it at (6,6,6)/11 = A + 3/11 (B-A) + 2/11 (C-A).
const Vec3 kA{1, 0, 0}, kB{0, 2, 0}, kC{0, 0, 3};
const Ray kDiagonal = makeRay({0, 0, 0}, {1, 1, 1});

TEST(Triangle, GeometricNormalIsBMinusACrossCMinusA) {
    Triangle tri = Triangle::fromVertices(kA, kB, kC);
    expectNear(tri.normalDirection(), {6, 3, 2});
    Primitives prims;
    prims.addTriangle(kA, kB, kC, nullptr, 3);
    Hit hit;
    ASSERT_TRUE(prims.intersect(0, TraversalRay(kDiagonal), hit));
    SurfaceInteraction si = prims.interaction(kDiagonal, hit);
    expectNear(si.ng, Vec3{6, 3, 2} / 7.0);
    expectNear(si.n, si.ng, 0);
    EXPECT_EQ(si.material, 3u);
}

TEST(Triangle, NormalIsNeverFlippedTowardsTheViewer) {
    Primitives prims;
    prims.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, nullptr, 0);  // counter-clockwise: +z
    prims.addTriangle({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, nullptr, 0);  // clockwise: -z
    for (double side : {1.0, -1.0}) {
        Ray ray = makeRay({0.25, 0.25, side}, {0, 0, -side});
        for (uint32_t id : {0u, 1u}) {
            Hit hit;
            ASSERT_TRUE(prims.intersect(id, TraversalRay(ray), hit));
            SurfaceInteraction si = prims.interaction(ray, hit);
            expectNear(si.ng, {0, 0, id == 0 ? 1.0 : -1.0});
            expectNear(si.p, {0.25, 0.25, 0});
        }
    }
}

TEST(Triangle, RefinedHitHasExactDistanceAndBarycentrics) {
    Triangle tri = Triangle::fromVertices(kA, kB, kC);
    auto t = trace(tri, kDiagonal);
    ASSERT_TRUE(t);
    double expected = 6 * std::sqrt(3.0) / 11;
    EXPECT_NEAR(*t, expected, 1e-6);
    TriangleHit th = refineTriangleHit(tri, kDiagonal, *t);
    EXPECT_NEAR(th.t, expected, 1e-15);
    EXPECT_NEAR(th.b1, 3.0 / 11, 1e-15);
    EXPECT_NEAR(th.b2, 2.0 / 11, 1e-15);

    Primitives prims;
    prims.addTriangle(kA, kB, kC, nullptr, 0);
    Hit hit;
    ASSERT_TRUE(prims.intersect(0, TraversalRay(kDiagonal), hit));
    expectNear(prims.interaction(kDiagonal, hit).p, Vec3{6, 6, 6} / 11.0, 1e-15);
}

TEST(Triangle, VertexNormalsAreInterpolatedWithTheBarycentrics) {
    // Weights at the hit: A 6/11, B 3/11, C 2/11.
    const Vec3 normals[3] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
    Primitives prims;
    prims.addTriangle(kA, kB, kC, normals, 0);
    Hit hit;
    ASSERT_TRUE(prims.intersect(0, TraversalRay(kDiagonal), hit));
    SurfaceInteraction si = prims.interaction(kDiagonal, hit);
    expectNear(si.n, Vec3{3, 2, 6} / 7.0);   // (3/11, 2/11, 6/11) normalised
    expectNear(si.ng, Vec3{6, 3, 2} / 7.0);  // the geometric normal is unchanged

    // At a vertex the shading normal is that vertex's normal.
    Ray atB = makeRay({0, 2, 1}, {0, 0, -1});
    Hit hitB;
    ASSERT_TRUE(prims.intersect(0, TraversalRay(atB), hitB));
    expectNear(prims.interaction(atB, hitB).n, {1, 0, 0});
}

TEST(Triangle, CancellingVertexNormalsFallBackToTheFaceNormal) {
    // At (0.25, 0.25) the weights are A 0.5, B 0.25, C 0.25: the normals sum to zero.
    const Vec3 opposed[3] = {{0, 0, 1}, {0, 0, -1}, {0, 0, -1}};
    const Vec3 zero[3] = {};
    Primitives prims;
    prims.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, opposed, 0);
    prims.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, zero, 0);
    for (uint32_t id : {0u, 1u}) {
        Hit hit;
        ASSERT_TRUE(prims.intersect(id, TraversalRay(down(0.25, 0.25)), hit));
        SurfaceInteraction si = prims.interaction(down(0.25, 0.25), hit);
        EXPECT_TRUE(isFinite(si.n));
        expectNear(si.n, {0, 0, 1});
        expectNear(si.ng, {0, 0, 1});
    }
}

TEST(Triangle, TrianglesComeBeforeSpheresInPrimitiveIds) {
    Primitives prims;
    prims.addSphere(Sphere{{0, 0, -5}, 1, {}}, 1);
    prims.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, nullptr, 2);
    ASSERT_EQ(prims.size(), 2u);
    EXPECT_EQ(prims.triangleCount(), 1u);
    EXPECT_EQ(prims.sphereCount(), 1u);
    Ray ray = down(0.25, 0.25);
    Hit tri, sph;
    EXPECT_TRUE(prims.intersect(0, TraversalRay(ray), tri));
    EXPECT_TRUE(prims.intersect(1, TraversalRay(ray), sph));
    EXPECT_EQ(tri.primId, 0u);
    EXPECT_EQ(sph.primId, 1u);
    EXPECT_EQ(tri.t, 1.0f);
    EXPECT_FLOAT_EQ(sph.t, static_cast<float>(6 - std::sqrt(1 - 0.125)));
    EXPECT_EQ(prims.interaction(ray, tri).material, 2u);
    EXPECT_EQ(prims.interaction(ray, sph).material, 1u);
}

}  // namespace
}  // namespace glint
