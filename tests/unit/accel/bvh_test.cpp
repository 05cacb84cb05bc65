#include "glint/accel/bvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "glint/accel/brute_force.h"
#include "glint/math/mat4.h"
#include "glint/math/rng.h"

namespace glint {
namespace {

class Random {
  public:
    explicit Random(uint64_t seed) : rng_(seed) {}
    double uni(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(rng_.uniform());
    }
    Vec3 point(double lo, double hi) { return {uni(lo, hi), uni(lo, hi), uni(lo, hi)}; }
    Vec3 direction() {
        for (;;) {
            Vec3 v = point(-1, 1);
            double l2 = dot(v, v);
            if (l2 > 1e-4 && l2 <= 1) return v / std::sqrt(l2);
        }
    }
    uint32_t below(uint32_t n) { return rng_.next() % n; }

  private:
    Rng rng_;
};

/// Random triangles of sizes from 0.01 to 10, spheres, and rotated, scaled ellipsoids, all
/// within about [-12, 12]^3.
void addRandomScene(Primitives& prims, Random& r, int triangles, int spheres) {
    for (int i = 0; i < triangles; ++i) {
        Vec3 c = r.point(-10, 10);
        double size = std::pow(10.0, r.uni(-2, 1));
        prims.addTriangle(c + r.direction() * size, c + r.direction() * size,
                          c + r.direction() * size, nullptr, 0);
    }
    for (int i = 0; i < spheres; ++i) {
        Vec3 c = r.point(-10, 10);
        Mat4 m = Mat4::translate(c.x, c.y, c.z);
        if (i % 2) {
            Vec3 axis = r.direction();
            m = m * Mat4::rotate(axis.x, axis.y, axis.z, r.uni(0, 360)) *
                Mat4::scale(r.uni(0.2, 2), r.uni(0.2, 2), r.uni(0.2, 2));
        }
        prims.addSphere(Sphere{r.point(-0.2, 0.2), r.uni(0.05, 1.5), *Transform::fromMatrix(m)}, 0);
    }
}

/// Rays from random origins: half aimed at a random primitive, some along the axes, a third
/// with a finite tMax, some with tMin > 0.
Ray randomRay(const Primitives& prims, Random& r, int i) {
    Vec3 origin = r.point(-15, 15);
    Vec3 dir = r.direction();
    if (i % 2 == 0 && prims.size() > 0) {
        Vec3 target(prims.bounds(r.below(prims.size())).centroid());
        if (length(target - origin) > 1e-3) dir = normalize(target - origin + r.point(-0.1, 0.1));
    }
    if (i % 11 == 0) {
        dir = {};
        dir[static_cast<int>(r.below(3))] = r.uni(0, 1) < 0.5 ? -1 : 1;
    }
    Ray ray{origin, dir, 0, kInfinity};
    if (i % 3 == 0) ray.tMax = r.uni(0.1, 30);
    if (i % 7 == 0) ray.tMin = r.uni(0, 5);
    return ray;
}

struct Agreement {
    int rays = 0, hits = 0, mismatches = 0;
    std::string first;
};

/// Compares BVH and brute force on one ray: hit/miss, exact t, and a tied primitive really
/// being at that distance; occluded for rays with finite tMax.
void compare(const Primitives& prims, const Bvh& bvh, const BruteForce& oracle, const Ray& ray,
             Agreement& a) {
    ++a.rays;
    Hit hb, ho;
    bool fb = bvh.intersect(ray, hb), fo = oracle.intersect(ray, ho);
    bool ok = fb == fo && (!fb || hb.t == ho.t);
    if (ok && fb && hb.primId != ho.primId) {
        Hit alone;
        ok = prims.intersect(hb.primId, TraversalRay(ray), alone) && alone.t == ho.t;
    }
    if (std::isfinite(ray.tMax) && bvh.occluded(ray) != oracle.occluded(ray)) ok = false;
    // A tMax at the closest hit: nothing strictly closer, so neither may report occlusion.
    if (fo) {
        Ray before = ray;
        before.tMax = static_cast<double>(ho.t);
        if (bvh.occluded(before) != oracle.occluded(before)) ok = false;
    }
    a.hits += fo;
    if (!ok && a.mismatches++ == 0)
        a.first = "ray " + std::to_string(a.rays) + ": bvh " + std::to_string(fb) + " t " +
                  std::to_string(hb.t) + " id " + std::to_string(hb.primId) + ", brute " +
                  std::to_string(fo) + " t " + std::to_string(ho.t) + " id " +
                  std::to_string(ho.primId);
}

Agreement compareOnRandomRays(const Primitives& prims, int rays, uint64_t seed) {
    Bvh bvh;
    bvh.build(prims);
    BruteForce oracle;
    oracle.build(prims);
    Random r(seed);
    Agreement a;
    for (int i = 0; i < rays; ++i) compare(prims, bvh, oracle, randomRay(prims, r, i), a);
    return a;
}

/// Structural checks: leaf sizes, depth, every primitive in exactly one leaf, children
/// inside their parent's box.
void expectSaneTree(const Bvh& bvh, uint32_t primCount) {
    const BvhStats& s = bvh.stats();
    const auto& nodes = bvh.nodes();
    EXPECT_LE(s.maxLeafSize, 8u);
    EXPECT_LE(s.maxDepth, static_cast<uint32_t>(Bvh::kMaxDepth));
    EXPECT_EQ(s.nodes, nodes.size());
    EXPECT_EQ(s.nodes, 2 * s.leaves - 1);
    uint32_t inLeaves = 0, leaves = 0;
    for (size_t i = 0; i < nodes.size(); ++i) {
        const BvhNode& n = nodes[i];
        if (n.count > 0) {
            ++leaves;
            inLeaves += n.count;
            EXPECT_LE(n.count, 8);
            EXPECT_LE(n.offset + n.count, primCount);
            continue;
        }
        ASSERT_LT(n.offset, nodes.size());
        ASSERT_GT(n.offset, i + 1);
        for (size_t child : {i + 1, static_cast<size_t>(n.offset)}) {
            const Bounds3f& c = nodes[child].bounds;
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(c.lo[a], n.bounds.lo[a]);
                EXPECT_LE(c.hi[a], n.bounds.hi[a]);
            }
        }
    }
    EXPECT_EQ(leaves, s.leaves);
    EXPECT_EQ(inLeaves, primCount);
}

TEST(Bvh, AgreesWithBruteForceOnMixedRandomPrimitives) {
    Primitives prims;
    Random r(2024);
    addRandomScene(prims, r, 1500, 300);
    Agreement a = compareOnRandomRays(prims, 5000, 99);
    EXPECT_EQ(a.mismatches, 0) << a.first;
    EXPECT_GT(a.hits, a.rays / 4);  // the comparison is not mostly misses
    EXPECT_LT(a.hits, a.rays);
}

TEST(Bvh, AgreesWithBruteForceOnALargeRandomSet) {
    Primitives prims;
    Random r(77);
    addRandomScene(prims, r, 20000, 2000);
    Bvh bvh;
    bvh.build(prims);
    expectSaneTree(bvh, prims.size());
    Agreement a = compareOnRandomRays(prims, 2000, 5);
    EXPECT_EQ(a.mismatches, 0) << a.first;
    EXPECT_GT(a.hits, a.rays / 2);
}

TEST(Bvh, AgreesOnEdgesAndVerticesOfAxisAlignedTriangles) {
    // Axis-aligned triangles have flat boxes; rays aimed exactly at their edges and corners
    // are where rounding in the box test could cull a hit that the triangle test accepts.
    Primitives prims;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
            auto x = static_cast<double>(i), y = static_cast<double>(j);
            prims.addTriangle({x, y, 0}, {x + 1, y, 0}, {x, y + 1, 0}, nullptr, 0);  // z = 0
            prims.addTriangle({x, 0, y}, {x + 1, 0, y}, {x, 0, y + 1}, nullptr, 0);  // y = 0
            prims.addTriangle({0, x, y}, {0, x + 1, y}, {0, x, y + 1}, nullptr, 0);  // x = 0
        }
    Bvh bvh;
    bvh.build(prims);
    BruteForce oracle;
    oracle.build(prims);
    Random r(11);
    Agreement a;
    for (int i = 0; i < 20000; ++i) {
        // A vertex or a point on a leg (u integer) or on a hypotenuse (u + v integer) of one
        // of the triangles, in one of the three planes.
        double u = static_cast<double>(r.below(13)) / 2, v = static_cast<double>(r.below(13)) / 2;
        if (r.below(2))
            u = std::floor(u);
        else
            v = std::floor(u + v) - u;
        if (r.below(2)) std::swap(u, v);
        int plane = static_cast<int>(r.below(3));
        Vec3 target = plane == 0 ? Vec3{u, v, 0} : (plane == 1 ? Vec3{u, 0, v} : Vec3{0, u, v});
        Vec3 origin = r.point(-3, 9);
        if (length(target - origin) < 1e-3) continue;
        compare(prims, bvh, oracle, Ray{origin, normalize(target - origin), 0, kInfinity}, a);
    }
    EXPECT_EQ(a.mismatches, 0) << a.first;
    EXPECT_GT(a.hits, a.rays / 2);
}

TEST(Bvh, EmptySceneHitsNothing) {
    Primitives prims;
    Bvh bvh;
    bvh.build(prims);
    Hit hit;
    EXPECT_FALSE(bvh.intersect(Ray{{0, 0, 0}, {0, 0, 1}, 0, kInfinity}, hit));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {0, 0, 1}, 0, 10}));
    EXPECT_EQ(bvh.stats().nodes, 0u);
    EXPECT_TRUE(bvh.nodes().empty());
}

TEST(Bvh, SinglePrimitiveIsOneLeaf) {
    Primitives prims;
    prims.addSphere(Sphere{{0, 0, 5}, 1, {}}, 0);
    Bvh bvh;
    bvh.build(prims);
    EXPECT_EQ(bvh.stats().nodes, 1u);
    EXPECT_EQ(bvh.stats().leaves, 1u);
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{0, 0, 0}, {0, 0, 1}, 0, kInfinity}, hit));
    EXPECT_EQ(hit.t, 4.0f);
    EXPECT_EQ(hit.primId, 0u);
    EXPECT_TRUE(bvh.occluded(Ray{{0, 0, 0}, {0, 0, 1}, 0, 4.5}));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {0, 0, 1}, 0, 3.5}));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {0, 1, 0}, 0, 100}));
}

TEST(Bvh, ThousandsOfIdenticalPrimitivesBuildAndAgree) {
    Primitives prims;
    for (int i = 0; i < 5000; ++i)
        prims.addTriangle({-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, nullptr, 0);
    Bvh bvh;
    bvh.build(prims);
    expectSaneTree(bvh, prims.size());
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{0, 0, 3}, {0, 0, -1}, 0, kInfinity}, hit));
    EXPECT_EQ(hit.t, 3.0f);
    Agreement a = compareOnRandomRays(prims, 300, 3);
    EXPECT_EQ(a.mismatches, 0) << a.first;
}

TEST(Bvh, ConcentricSpheresWithOneCentroidAgree) {
    // All centroids equal, sizes differ: the outermost sphere must win from outside.
    Primitives prims;
    for (int i = 1; i <= 2000; ++i) prims.addSphere(Sphere{{1, 2, 3}, 0.005 * i, {}}, 0);
    Bvh bvh;
    bvh.build(prims);
    expectSaneTree(bvh, prims.size());
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{1, 2, -20}, {0, 0, 1}, 0, kInfinity}, hit));
    EXPECT_FLOAT_EQ(hit.t, 13.0f);
    EXPECT_EQ(hit.primId, 1999u);
    Agreement a = compareOnRandomRays(prims, 300, 4);
    EXPECT_EQ(a.mismatches, 0) << a.first;
}

TEST(Bvh, GeometricallySpacedPrimitivesStayWithinTheDepthBound) {
    // Centroids at 1.02^i along x, sizes growing alike: a skewed set for the SAH.
    Primitives prims;
    for (int i = 0; i < 3000; ++i) {
        double x = std::pow(1.02, i), s = 0.01 * x;
        prims.addTriangle({x, 0, 0}, {x + s, 0, 0}, {x, s, s}, nullptr, 0);
    }
    Bvh bvh;
    bvh.build(prims);
    expectSaneTree(bvh, prims.size());
    Agreement a = compareOnRandomRays(prims, 500, 6);
    EXPECT_EQ(a.mismatches, 0) << a.first;
}

TEST(Bvh, RebuildingReplacesTheTree) {
    Primitives big, small;
    Random r(1);
    addRandomScene(big, r, 500, 50);
    small.addSphere(Sphere{{0, 0, 5}, 1, {}}, 0);
    Bvh bvh;
    bvh.build(big);
    bvh.build(small);
    EXPECT_EQ(bvh.stats().nodes, 1u);
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{0, 0, 0}, {0, 0, 1}, 0, kInfinity}, hit));
    EXPECT_EQ(hit.primId, 0u);
}

}  // namespace
}  // namespace glint
