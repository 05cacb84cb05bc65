#include "glint/geometry/polygon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "glint/geometry/primitives.h"
#include "glint/math/mat4.h"
#include "glint/math/rng.h"
#include "glint/math/transform.h"
#include "unit/test_support.h"

namespace glint {
namespace {

using test::expectNear;
using Problem = PolygonTriangulation::Problem;

std::vector<Vec3> flat(const std::vector<std::array<double, 2>>& xy, double z = 0) {
    std::vector<Vec3> p;
    for (auto [x, y] : xy) p.push_back({x, y, z});
    return p;
}

/// Area of the polygon by the shoelace formula along `normal`.
double polygonArea(const std::vector<Vec3>& p, const Vec3& normal) {
    Vec3 sum(0);
    for (size_t i = 0; i < p.size(); ++i) sum += cross(p[i], p[(i + 1) % p.size()]);
    return dot(sum, normal) / 2;
}

/// Checks what every triangulation must satisfy: n - 2 triangles, each a proper triangle of
/// the polygon's vertices turning along the normal, together exactly the polygon's area.
void expectGoodTriangulation(const std::vector<Vec3>& p, const PolygonTriangulation& r) {
    ASSERT_EQ(r.problem, Problem::None);
    EXPECT_EQ(r.triangles.size(), p.size() - 2);
    double area = 0;
    for (const auto& t : r.triangles) {
        for (uint32_t i : t) ASSERT_LT(i, p.size());
        Vec3 n = cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
        EXPECT_GT(dot(n, r.normal), 0) << "a triangle turns the wrong way or has no area";
        area += length(n) / 2;
    }
    EXPECT_NEAR(area, polygonArea(p, r.normal), 1e-9 * area);
}

/// Whether a ray straight down through (x, y) hits the triangulated polygon at z = 0.
bool covers(const std::vector<Vec3>& p, const PolygonTriangulation& r, double x, double y) {
    Primitives prims;
    for (const auto& t : r.triangles) prims.addTriangle(p[t[0]], p[t[1]], p[t[2]], nullptr, 0);
    Ray ray{{x, y, 5}, {0, 0, -1}, 0, kInfinity};
    Hit hit;
    for (uint32_t id = 0; id < prims.size(); ++id) prims.intersect(id, TraversalRay(ray), hit);
    return std::isfinite(hit.t);
}

TEST(Polygon, ConvexSquareCounterClockwiseFacesUp) {
    auto p = flat({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    PolygonTriangulation r = triangulatePolygon(p);
    expectGoodTriangulation(p, r);
    expectNear(r.normal, {0, 0, 1});
    EXPECT_TRUE(covers(p, r, 0.5, 0.5));
    EXPECT_FALSE(covers(p, r, 1.5, 0.5));
}

TEST(Polygon, ClockwiseOrderFacesDown) {
    auto p = flat({{0, 0}, {0, 1}, {1, 1}, {1, 0}});
    PolygonTriangulation r = triangulatePolygon(p);
    expectGoodTriangulation(p, r);
    expectNear(r.normal, {0, 0, -1});
}

TEST(Polygon, ConcaveLShapeCoversItsArmsButNotTheNotch) {
    auto p = flat({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}});
    PolygonTriangulation r = triangulatePolygon(p);
    expectGoodTriangulation(p, r);
    EXPECT_TRUE(covers(p, r, 2.5, 0.5));
    EXPECT_TRUE(covers(p, r, 0.5, 2.5));
    EXPECT_TRUE(covers(p, r, 0.5, 0.5));
    EXPECT_FALSE(covers(p, r, 2, 2));  // the notch
    EXPECT_FALSE(covers(p, r, 1.5, 1.5));
}

TEST(Polygon, FivePointedStarCoversItsPointsButNotTheGapsBetween) {
    std::vector<Vec3> p;
    const double pi = std::acos(-1.0);
    for (int i = 0; i < 10; ++i) {
        double a = pi / 2 + i * pi / 5, r = i % 2 ? 0.4 : 1;
        p.push_back({r * std::cos(a), r * std::sin(a), 0});
    }
    PolygonTriangulation r = triangulatePolygon(p);
    expectGoodTriangulation(p, r);
    EXPECT_TRUE(covers(p, r, 0, 0));
    EXPECT_TRUE(covers(p, r, 0, 0.9));     // the top point
    EXPECT_FALSE(covers(p, r, 0, -0.9));   // between the two lower points
    EXPECT_FALSE(covers(p, r, 0.7, 0.6));  // between the top and the right point
}

TEST(Polygon, CollinearVerticesStayCornersWithoutZeroAreaTriangles) {
    // A 2 x 1 rectangle with extra vertices along its edges, and three in a row at a corner.
    auto p = flat(
        {{0, 0}, {0.5, 0}, {1, 0}, {1.5, 0}, {2, 0}, {2, 0.5}, {2, 1}, {1, 1}, {0, 1}, {0, 0.5}});
    PolygonTriangulation r = triangulatePolygon(p);
    expectGoodTriangulation(p, r);
    EXPECT_TRUE(covers(p, r, 1.9, 0.1));
    EXPECT_TRUE(covers(p, r, 0.1, 0.9));
    // The same in a tilted plane with decimal coordinates (collinear only up to rounding).
    Transform t =
        *Transform::fromMatrix(Mat4::rotate(1, 2, 3, 37) * Mat4::translate(0.1, 0.2, 0.3));
    std::vector<Vec3> q;
    for (const Vec3& v : p) q.push_back(t.point(v));
    PolygonTriangulation rq = triangulatePolygon(q);
    expectGoodTriangulation(q, rq);
    expectNear(rq.normal, normalize(t.normal({0, 0, 1})), 1e-12);
}

TEST(Polygon, RandomStarShapedPolygonsTriangulateExactly) {
    Rng rng(7);
    for (int k = 0; k < 200; ++k) {
        int n = 3 + static_cast<int>(rng.next() % 40);
        std::vector<Vec3> p;
        const double pi = std::acos(-1.0);
        for (int i = 0; i < n; ++i) {
            double a = 2 * pi * (i + 0.8 * rng.uniform()) / n, r = 0.2 + rng.uniform();
            p.push_back({r * std::cos(a), r * std::sin(a), 0.1 * r * std::cos(a)});
        }
        PolygonTriangulation r = triangulatePolygon(p);
        expectGoodTriangulation(p, r);
    }
}

TEST(Polygon, TriangleIsItself) {
    auto p = flat({{0, 0}, {1, 0}, {0, 1}});
    PolygonTriangulation r = triangulatePolygon(p);
    expectGoodTriangulation(p, r);
}

TEST(Polygon, RepeatedPositionIsNamed) {
    auto p = flat({{0, 0}, {1, 0}, {1, 1}, {1, 0}});
    PolygonTriangulation r = triangulatePolygon(p);
    EXPECT_EQ(r.problem, Problem::SamePosition);
    EXPECT_EQ(r.vertex, 3);
    EXPECT_EQ(r.other, 1);
}

TEST(Polygon, CollinearVerticesOnlyHaveZeroArea) {
    EXPECT_EQ(triangulatePolygon(flat({{0, 0}, {1, 1}, {3, 3}})).problem, Problem::ZeroArea);
    EXPECT_EQ(triangulatePolygon(flat({{0, 0}, {1, 0}, {2, 0}, {3, 0}})).problem,
              Problem::ZeroArea);
}

TEST(Polygon, NonPlanarVertexIsNamed) {
    std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0.1}, {0, 1, 0}};
    PolygonTriangulation r = triangulatePolygon(p);
    EXPECT_EQ(r.problem, Problem::NonPlanar);
    EXPECT_EQ(r.vertex, 2);
    EXPECT_GT(r.offPlane, kPolygonPlanarity);
    // Within the tolerance it is accepted.
    p[2].z = 1e-5;
    EXPECT_EQ(triangulatePolygon(p).problem, Problem::None);
}

TEST(Polygon, SelfIntersectionsAreFound) {
    // A lopsided bow tie: edge 2-3 crosses edge 0-1. (A symmetric one has zero area.)
    PolygonTriangulation bow = triangulatePolygon(flat({{0, 0}, {2, 2}, {2, 0}, {0, 1}}));
    EXPECT_EQ(bow.problem, Problem::SelfIntersecting);
    EXPECT_EQ(bow.vertex, 2);
    EXPECT_EQ(bow.other, 0);
    // A vertex touching a non-adjacent edge.
    EXPECT_EQ(triangulatePolygon(flat({{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}})).problem,
              Problem::SelfIntersecting);
    // Two neighbouring edges folding back onto each other.
    EXPECT_EQ(triangulatePolygon(flat({{0, 0}, {2, 0}, {1, 0}, {1, 1}})).problem,
              Problem::SelfIntersecting);
}

TEST(Polygon, ManyVerticesTakeQuadraticTimeAtMost) {
    // A comb with 1000 vertices: many reflex corners (an ear-clipping worst case).
    std::vector<Vec3> p;
    const int teeth = 249;
    for (int i = 0; i < teeth; ++i) {
        double x = i;
        p.push_back({x, 0, 0});
        p.push_back({x + 0.25, 10, 0});
        p.push_back({x + 0.5, 0.5, 0});
        p.push_back({x + 0.75, 10, 0});
    }
    p.push_back({teeth, 0, 0});
    p.push_back({teeth, -1, 0});
    p.push_back({0, -1, 0});
    PolygonTriangulation r = triangulatePolygon(p);
    expectGoodTriangulation(p, r);
}

}  // namespace
}  // namespace glint
