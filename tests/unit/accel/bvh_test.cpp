#include "glint/accel/bvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "glint/accel/brute_force.h"
#include "glint/accel/bvh_build.h"
#include "glint/core/parallel.h"
#include "glint/math/mat4.h"
#include "glint/math/rng.h"
#include "unit/random_geometry.h"

namespace glint {
namespace {

using test::Random;

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

/// A random affine map: translation within [-10, 10]^3, rotation, scale 0.3 to 2 per axis.
Mat4 randomTransform(Random& r) {
    Vec3 c = r.point(-10, 10), axis = r.direction();
    return Mat4::translate(c.x, c.y, c.z) * Mat4::rotate(axis.x, axis.y, axis.z, r.uni(0, 360)) *
           Mat4::scale(r.uni(0.3, 2), r.uni(0.3, 2), r.uni(0.3, 2));
}

/// Boxes, cylinders, cones (pointed and frustums) and disks of sizes 0.1 to 2 under random
/// transforms (non-uniform scale and rotation), and `planes` planes below and beside it all.
void addRandomShapes(Primitives& prims, Random& r, int shapes, int planes) {
    for (int i = 0; i < shapes; ++i) {
        Mat4 placement;
        double k = 1;
        auto kind = static_cast<ShapeKind>(1 + i % 4);
        double size = r.uni(0.1, 2);
        Vec3 a = r.point(-size, size), b = r.point(-size, size);
        switch (kind) {
            case ShapeKind::Box:
                placement = boxPlacement(a, b);
                break;
            case ShapeKind::Cylinder:
                placement = cylinderPlacement(a, b, r.uni(0.05, size));
                break;
            case ShapeKind::Cone:
                placement = conePlacement(a, r.uni(0.05, size), b, i % 3 ? r.uni(0, size) : 0, k);
                break;
            default:
                placement = diskPlacement(a, r.direction(), size);
        }
        auto t = Transform::fromMatrix(randomTransform(r) * placement);
        ASSERT_TRUE(t);
        prims.addShape(Shape{kind, k, *t}, 0);
    }
    for (int i = 0; i < planes; ++i) {
        Vec3 normal = normalize(Vec3(0, 1, 0) + r.point(-0.3, 0.3));
        if (i % 2) normal = normalize(Vec3(1, 0, 0) + r.point(-0.3, 0.3));
        auto plane = Plane::make(normal * -13.0, normal, Transform{});
        ASSERT_TRUE(plane);
        prims.addPlane(*plane, 0);
    }
}

/// Every kind of primitive: triangles, spheres, the other shapes and planes.
void addAllKinds(Primitives& prims, Random& r, int triangles, int spheres, int shapes, int planes) {
    addRandomScene(prims, r, triangles, spheres);
    addRandomShapes(prims, r, shapes, planes);
}

/// Rays from random origins: half aimed at a random primitive, some along the axes, a third
/// with a finite tMax, some with tMin > 0.
Ray randomRay(const Primitives& prims, Random& r, int i) {
    Vec3 origin = r.point(-15, 15);
    Vec3 dir = r.direction();
    if (i % 2 == 0 && prims.boundedCount() > 0) {
        Vec3 target(prims.bounds(r.below(prims.boundedCount())).centroid());
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
    // With the tie rule (lowest id among equal distances) the answers are identical.
    bool ok = fb == fo && (!fb || (hb.t == ho.t && hb.primId == ho.primId));
    if (ok && fb && prims.isInstance(hb.primId)) ok = hb.subId == ho.subId;
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

Agreement compareOnRandomRays(const Primitives& prims, int rays, uint64_t seed, Isa isa) {
    Bvh bvh;
    bvh.build(prims, {0, isa});
    BruteForce oracle;
    oracle.build(prims);
    Random r(seed);
    Agreement a;
    for (int i = 0; i < rays; ++i) compare(prims, bvh, oracle, randomRay(prims, r, i), a);
    return a;
}

/// Structural checks on the 8-wide layout: every primitive in exactly one leaf, leaf sizes and
/// depth within bounds, every child inside the box its parent stores for it, unused slots
/// empty.
void expectSaneTree(const Bvh& bvh, const Primitives& prims) {
    const BvhStats& s = bvh.stats();
    const bvh::BvhData& d = bvh.data();
    EXPECT_LE(s.maxLeafSize, 8u);
    EXPECT_LE(s.maxDepth, bvh::kMaxDepth);
    EXPECT_EQ(s.nodes, d.nodes.size());
    std::vector<int> seen(prims.boundedCount(), 0);
    uint32_t leaves = 0;
    auto inside = [](const Bounds3f& inner, const Bounds3f& outer) {
        for (int a = 0; a < 3; ++a)
            if (inner.lo[a] < outer.lo[a] || inner.hi[a] > outer.hi[a]) return false;
        return true;
    };
    // Visits `ref`, whose box in its parent is `box` (everything for the root).
    std::function<void(bvh::NodeRef, const Bounds3f&)> visit = [&](bvh::NodeRef ref,
                                                                   const Bounds3f& box) {
        if (bvh::isLeaf(ref)) {
            ++leaves;
            uint32_t first = bvh::leafFirst(ref), count = bvh::leafCount(ref);
            std::vector<uint32_t> ids;
            bool shapes = bvh::isSphereLeaf(ref) || bvh::isShapeRunLeaf(ref);
            if (bvh::isShapeRunLeaf(ref)) {
                ASSERT_LT(first, d.shapeRuns.size());
                bvh::ShapeRun run = d.shapeRuns[first];
                first = run.first, count = run.count;
            }
            if (shapes) {
                EXPECT_GE(count, 1u);
                for (uint32_t i = first; i < first + count; ++i) {
                    ids.push_back(d.shapeIds[i]);
                    if (bvh::isSphereLeaf(ref)) {
                        EXPECT_TRUE(prims.isSphere(d.shapeIds[i]));
                    }
                }
            } else {
                for (uint32_t b = first; b < first + count; ++b)
                    for (uint32_t id : d.tris[b].id)
                        if (id != bvh::kEmpty) ids.push_back(id);
            }
            EXPECT_LE(ids.size(), 8u);
            for (uint32_t id : ids) {
                ASSERT_LT(id, prims.boundedCount());
                ++seen[id];
                EXPECT_EQ(id >= prims.triangleCount(), shapes);
                EXPECT_TRUE(inside(prims.bounds(id), box)) << "primitive " << id;
            }
            return;
        }
        ASSERT_LT(ref, d.nodes.size());
        const bvh::Node8& n = d.nodes[ref];
        int used = 0;
        for (int i = 0; i < bvh::kWidth; ++i) {
            Bounds3f child{{n.lo[0][i], n.lo[1][i], n.lo[2][i]},
                           {n.hi[0][i], n.hi[1][i], n.hi[2][i]}};
            if (n.child[i] == bvh::kEmpty) {
                EXPECT_TRUE(child.empty());
                continue;
            }
            ++used;
            EXPECT_TRUE(inside(child, box));
            visit(n.child[i], child);
        }
        EXPECT_GE(used, 2);
    };
    if (d.root != bvh::kEmpty) visit(d.root, prims.bounds());
    EXPECT_EQ(leaves, s.leaves);
    for (uint32_t id = 0; id < prims.boundedCount(); ++id)
        EXPECT_EQ(seen[id], 1) << "primitive " << id;
    EXPECT_EQ(d.planeIds.size(), prims.planeCount());  // planes beside the tree, not in it
}

/// The kernel sets this build and CPU can run: every test below runs once per set.
std::vector<Isa> kernelSets() {
    std::vector<Isa> sets{Isa::Portable};
#if GLINT_HAVE_AVX2
    if (__builtin_cpu_supports("avx2")) sets.push_back(Isa::Avx2);
#endif
    return sets;
}

class BvhKernels : public testing::TestWithParam<Isa> {
  protected:
    Bvh build(const Primitives& prims, int threads = 0) {
        Bvh bvh;
        bvh.build(prims, {threads, GetParam()});
        EXPECT_EQ(bvh.kernels(), GetParam());
        return bvh;
    }
};

TEST_P(BvhKernels, AgreesWithBruteForceOnMixedRandomPrimitives) {
    Primitives prims;
    Random r(2024);
    addRandomScene(prims, r, 1500, 300);
    Agreement a = compareOnRandomRays(prims, 5000, 99, GetParam());
    EXPECT_EQ(a.mismatches, 0) << a.first;
    EXPECT_GT(a.hits, a.rays / 4);  // the comparison is not mostly misses
    EXPECT_LT(a.hits, a.rays);
}

TEST_P(BvhKernels, AgreesWithBruteForceOnEveryKindUnderRandomTransforms) {
    Primitives prims;
    Random r(314);
    addAllKinds(prims, r, 800, 150, 600, 2);
    Bvh bvh = build(prims);
    expectSaneTree(bvh, prims);
    Agreement a = compareOnRandomRays(prims, 6000, 17, GetParam());
    EXPECT_EQ(a.mismatches, 0) << a.first;
    EXPECT_GT(a.hits, a.rays / 4);
    EXPECT_LT(a.hits, a.rays);
}

TEST_P(BvhKernels, AgreesWithBruteForceOnShapesAlone) {
    // Shape runs only (no triangles, no spheres), many per leaf region.
    Primitives prims;
    Random r(2718);
    addRandomShapes(prims, r, 3000, 0);
    Bvh bvh = build(prims);
    expectSaneTree(bvh, prims);
    EXPECT_FALSE(bvh.data().shapeRuns.empty());
    Agreement a = compareOnRandomRays(prims, 4000, 18, GetParam());
    EXPECT_EQ(a.mismatches, 0) << a.first;
    EXPECT_GT(a.hits, a.rays / 2);
}

TEST_P(BvhKernels, SphereScenesUseSphereLeavesOnly) {
    Primitives prims;
    Random r(99);
    addRandomScene(prims, r, 0, 500);
    Bvh bvh = build(prims);
    expectSaneTree(bvh, prims);
    EXPECT_TRUE(bvh.data().shapeRuns.empty());
}

TEST_P(BvhKernels, PlanesAloneAreFoundByEveryQuery) {
    Primitives prims;
    prims.addPlane(*Plane::make({0, -1, 0}, {0, 1, 0}, Transform{}), 0);
    prims.addPlane(*Plane::make({0, 0, -5}, {0, 0, 3}, Transform{}), 0);
    Bvh bvh = build(prims);
    EXPECT_EQ(bvh.data().root, bvh::kEmpty);
    EXPECT_TRUE(bvh.bounds().empty());  // planes are not part of the scene bounds
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{0, 0, 0}, normalize(Vec3(0, -1, -1)), 0, kInfinity}, hit));
    EXPECT_EQ(hit.primId, 0u);  // both at sqrt(2): the lower id wins the tie
    EXPECT_FLOAT_EQ(hit.t, std::sqrt(2.0f));
    EXPECT_TRUE(bvh.occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0, 5.5}));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0, 4.5}));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {0, 1, 0}, 0, kInfinity}));
    RayPacket8 packet;
    for (int i = 0; i < 8; ++i)
        packet.set(i, TraversalRay(Ray{{0, 0, 0}, normalize(Vec3(0, -1, -0.1 * i)), 0, kInfinity}));
    packet.active = 0x7f;
    HitPacket8 hits;
    bvh.intersect8(packet, hits);
    for (int i = 0; i < 7; ++i) {
        Hit single;
        ASSERT_TRUE(bvh.intersect(packet.ray(i), single));
        EXPECT_EQ(hits.t[i], single.t);
        EXPECT_EQ(hits.primId[i], single.primId);
    }
    EXPECT_TRUE(std::isinf(hits.t[7]));  // inactive
}

TEST_P(BvhKernels, AgreesWithBruteForceOnALargeRandomSet) {
    Primitives prims;
    Random r(77);
    addRandomScene(prims, r, 20000, 2000);
    Bvh bvh = build(prims);
    expectSaneTree(bvh, prims);
    Agreement a = compareOnRandomRays(prims, 2000, 5, GetParam());
    EXPECT_EQ(a.mismatches, 0) << a.first;
    EXPECT_GT(a.hits, a.rays / 2);
}

TEST_P(BvhKernels, AgreesOnEdgesAndVerticesOfAxisAlignedTriangles) {
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
    Bvh bvh = build(prims);
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

TEST_P(BvhKernels, EmptySceneHitsNothing) {
    Primitives prims;
    Bvh bvh = build(prims);
    Hit hit;
    EXPECT_FALSE(bvh.intersect(Ray{{0, 0, 0}, {0, 0, 1}, 0, kInfinity}, hit));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {0, 0, 1}, 0, 10}));
    EXPECT_EQ(bvh.stats().nodes, 0u);
    EXPECT_EQ(bvh.data().root, bvh::kEmpty);
}

TEST_P(BvhKernels, SinglePrimitiveIsOneLeaf) {
    Primitives prims;
    prims.addSphere(Sphere{{0, 0, 5}, 1, {}}, 0);
    Bvh bvh = build(prims);
    EXPECT_EQ(bvh.stats().nodes, 0u);  // the root is a leaf
    EXPECT_EQ(bvh.stats().leaves, 1u);
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{0, 0, 0}, {0, 0, 1}, 0, kInfinity}, hit));
    EXPECT_EQ(hit.t, 4.0f);
    EXPECT_EQ(hit.primId, 0u);
    EXPECT_TRUE(bvh.occluded(Ray{{0, 0, 0}, {0, 0, 1}, 0, 4.5}));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {0, 0, 1}, 0, 3.5}));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {0, 1, 0}, 0, 100}));
}

TEST_P(BvhKernels, ThousandsOfIdenticalPrimitivesBuildAndAgree) {
    Primitives prims;
    for (int i = 0; i < 5000; ++i)
        prims.addTriangle({-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, nullptr, 0);
    Bvh bvh = build(prims);
    expectSaneTree(bvh, prims);
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{0, 0, 3}, {0, 0, -1}, 0, kInfinity}, hit));
    EXPECT_EQ(hit.t, 3.0f);
    Agreement a = compareOnRandomRays(prims, 300, 3, GetParam());
    EXPECT_EQ(a.mismatches, 0) << a.first;
}

TEST_P(BvhKernels, ConcentricSpheresWithOneCentroidAgree) {
    // All centroids equal, sizes differ: the outermost sphere must win from outside.
    Primitives prims;
    for (int i = 1; i <= 2000; ++i) prims.addSphere(Sphere{{1, 2, 3}, 0.005 * i, {}}, 0);
    Bvh bvh = build(prims);
    expectSaneTree(bvh, prims);
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{1, 2, -20}, {0, 0, 1}, 0, kInfinity}, hit));
    EXPECT_FLOAT_EQ(hit.t, 13.0f);
    EXPECT_EQ(hit.primId, 1999u);
    Agreement a = compareOnRandomRays(prims, 300, 4, GetParam());
    EXPECT_EQ(a.mismatches, 0) << a.first;
}

TEST_P(BvhKernels, GeometricallySpacedPrimitivesStayWithinTheDepthBound) {
    // Centroids at 1.02^i along x, sizes growing alike: a skewed set for the SAH.
    Primitives prims;
    for (int i = 0; i < 3000; ++i) {
        double x = std::pow(1.02, i), s = 0.01 * x;
        prims.addTriangle({x, 0, 0}, {x + s, 0, 0}, {x, s, s}, nullptr, 0);
    }
    Bvh bvh = build(prims);
    expectSaneTree(bvh, prims);
    Agreement a = compareOnRandomRays(prims, 500, 6, GetParam());
    EXPECT_EQ(a.mismatches, 0) << a.first;
}

TEST_P(BvhKernels, RebuildingReplacesTheTree) {
    Primitives big, small;
    Random r(1);
    addRandomScene(big, r, 500, 50);
    small.addSphere(Sphere{{0, 0, 5}, 1, {}}, 0);
    Bvh bvh = build(big);
    bvh.build(small, {0, GetParam()});
    EXPECT_EQ(bvh.stats().nodes, 0u);  // one primitive: the root is a leaf
    EXPECT_EQ(bvh.stats().leaves, 1u);
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{0, 0, 0}, {0, 0, 1}, 0, kInfinity}, hit));
    EXPECT_EQ(hit.primId, 0u);
}

/// Packets of three kinds: a thin cone from one origin (camera rays), rays from nearby origins in
/// similar directions (shadow or reflection rays of neighbouring pixels), and unrelated rays.
RayPacket8 randomPacket(const Primitives& prims, Random& r, int p, Ray (&rays)[8]) {
    RayPacket8 packet;
    packet.active = static_cast<uint8_t>(p % 5 == 0 ? r.below(256) : 0xff);
    Vec3 origin = r.point(-15, 15), base = r.direction();
    for (int i = 0; i < 8; ++i) {
        switch (p % 3) {
            case 0:
                rays[i] = Ray{origin, normalize(base + r.point(-0.05, 0.05)), 0, kInfinity};
                break;
            case 1:
                rays[i] = Ray{origin + r.point(-0.1, 0.1), normalize(base + r.point(-0.05, 0.05)),
                              0, r.uni(0, 1) < 0.5 ? kInfinity : r.uni(1, 30)};
                break;
            default:
                rays[i] = randomRay(prims, r, i);
        }
        packet.set(i, TraversalRay(rays[i]));
    }
    return packet;
}

TEST_P(BvhKernels, PacketsGiveTheSameHitsAsSingleRays) {
    Primitives prims;
    Random r(31);
    addAllKinds(prims, r, 3000, 300, 300, 2);
    Bvh bvh = build(prims);
    int lanes = 0;
    for (int p = 0; p < 600; ++p) {
        Ray rays[8];
        RayPacket8 packet = randomPacket(prims, r, p, rays);
        HitPacket8 hits;
        bvh.intersect8(packet, hits);
        for (int i = 0; i < 8; ++i) {
            Hit single;
            bool found = (packet.active >> i & 1) && bvh.intersect(packet.ray(i), single);
            EXPECT_EQ(hits.t[i], single.t) << "packet " << p << " lane " << i;
            if (found) {
                EXPECT_EQ(hits.primId[i], single.primId);
            }
            lanes += found;
        }
    }
    EXPECT_GT(lanes, 600);
}

/// Whether two BVHs are the same byte for byte.
void expectSameTree(const Bvh& one, const Bvh& other) {
    const bvh::BvhData &a = one.data(), &b = other.data();
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    ASSERT_EQ(a.tris.size(), b.tris.size());
    ASSERT_EQ(a.shapes.size(), b.shapes.size());
    EXPECT_EQ(a.root, b.root);
    EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(bvh::Node8)), 0);
    EXPECT_EQ(std::memcmp(a.tris.data(), b.tris.data(), a.tris.size() * sizeof(bvh::Tri4)), 0);
    EXPECT_EQ(std::memcmp(a.shapes.data(), b.shapes.data(), a.shapes.size() * sizeof(ShapeSearch)),
              0);
    EXPECT_EQ(a.shapeIds, b.shapeIds);
    ASSERT_EQ(a.shapeRuns.size(), b.shapeRuns.size());
    for (size_t i = 0; i < a.shapeRuns.size(); ++i) {
        EXPECT_EQ(a.shapeRuns[i].first, b.shapeRuns[i].first);
        EXPECT_EQ(a.shapeRuns[i].count, b.shapeRuns[i].count);
    }
    EXPECT_EQ(one.stats().leaves, other.stats().leaves);
    EXPECT_EQ(one.stats().maxDepth, other.stats().maxDepth);
}

TEST(Bvh, TheTreeDoesNotDependOnTheBuildThreadCount) {
    // Enough primitives for every parallel phase: references in chunks, binning in chunks
    // (ranges of 2^16 and more), splits as tasks within a round (2^15), subtree tasks. The
    // kernels play no part in the build.
    Primitives prims;
    Random r(8);
    addAllKinds(prims, r, 160000, 2000, 2000, 1);
    Bvh one;
    one.build(prims, {.threads = 1});
    for (int threads : {2, 4}) {
        SCOPED_TRACE(testing::Message() << threads << " threads");
        Bvh own;
        own.build(prims, {.threads = threads});
        expectSameTree(one, own);
        // On a pool of the caller's, from the calling thread and from inside the pool's tasks
        // (two at once: their waits nest in each other's).
        ThreadPool pool(threads);
        Bvh viaPool;
        viaPool.build(prims, {.pool = &pool});
        expectSameTree(one, viaPool);
        Bvh inTasks[2];
        TaskGroup group(pool);
        for (Bvh& b : inTasks) group.run([&] { b.build(prims, {.pool = &pool}); });
        group.wait();
        for (const Bvh& b : inTasks) expectSameTree(one, b);
    }
}

TEST(Bvh, KernelSetsGiveIdenticalHits) {
    // The portable kernels are the reference: every other set must match them bit for bit.
    Primitives prims;
    Random r(5);
    addAllKinds(prims, r, 5000, 500, 500, 2);
    Bvh reference;
    reference.build(prims, {0, Isa::Portable});
    for (Isa isa : kernelSets()) {
        Bvh other;
        other.build(prims, {0, isa});
        Random rays(6);
        int differ = 0;
        for (int i = 0; i < 5000; ++i) {
            Ray ray = randomRay(prims, rays, i);
            Hit a, b;
            bool fa = reference.intersect(ray, a), fb = other.intersect(ray, b);
            differ += fa != fb || a.t != b.t || a.primId != b.primId ||
                      reference.occluded(ray) != other.occluded(ray);
        }
        EXPECT_EQ(differ, 0) << Bvh::name(isa);
    }
}

/// A two-level scene: shared meshes of random triangles around the origin, each with its BVH,
/// placed many times under random transforms among other primitives of every kind.
class InstancedScene {
  public:
    InstancedScene(uint64_t seed, int meshes, int instances, Isa isa) : r_(seed) {
        for (int m = 0; m < meshes; ++m) {
            auto mesh = std::make_unique<Primitives>();
            addRandomMesh(*mesh, 200 + 150 * m);
            meshes_.push_back(std::move(mesh));
            auto meshBvh = std::make_unique<Bvh>();
            meshBvh->build(*meshes_.back(), {0, isa});
            meshBvhs_.push_back(std::move(meshBvh));
            EXPECT_EQ(prims.addSharedMesh(*meshes_.back()), static_cast<uint32_t>(m));
        }
        addAllKinds(prims, r_, 500, 100, 100, 1);
        for (int i = 0; i < instances; ++i)
            prims.addInstance(static_cast<uint32_t>(i % meshes),
                              *Transform::fromMatrix(randomTransform(r_)));
        BvhBuildOptions options{0, isa};
        for (const auto& b : meshBvhs_) options.sharedMeshes.push_back(b.get());
        bvh.build(prims, options);
    }

    Primitives prims;
    Bvh bvh;
    Random& random() { return r_; }

  private:
    /// Triangles of sizes 0.05 to 0.5 within about [-1.5, 1.5]^3, some sharing an edge.
    void addRandomMesh(Primitives& mesh, int triangles) {
        for (int i = 0; i < triangles; ++i) {
            Vec3 c = r_.point(-1, 1);
            double size = r_.uni(0.05, 0.5);
            Vec3 a = c + r_.direction() * size, b = c + r_.direction() * size;
            mesh.addTriangle(a, b, c + r_.direction() * size, nullptr, 0);
            if (i % 5 == 0) mesh.addTriangle(b, a, c - r_.direction() * size, nullptr, 0);
        }
    }

    Random r_;
    std::vector<std::unique_ptr<Primitives>> meshes_;
    std::vector<std::unique_ptr<Bvh>> meshBvhs_;
};

TEST_P(BvhKernels, InstancesAgreeWithBruteForce) {
    InstancedScene scene(77, 3, 30, GetParam());
    const Primitives& prims = scene.prims;
    EXPECT_EQ(prims.instanceCount(), 30u);
    expectSaneTree(scene.bvh, prims);
    BruteForce oracle;
    oracle.build(prims);
    Agreement a;
    int instanceHits = 0;
    for (int i = 0; i < 1500; ++i) {
        Ray ray = randomRay(prims, scene.random(), i);
        compare(prims, scene.bvh, oracle, ray, a);
        Hit h;
        instanceHits += scene.bvh.intersect(ray, h) && prims.isInstance(h.primId);
    }
    EXPECT_EQ(a.mismatches, 0) << a.first;
    EXPECT_GT(instanceHits, a.rays / 20);  // instances are really hit, not just the rest
    EXPECT_LT(a.hits, a.rays);
}

TEST_P(BvhKernels, PacketsHitInstancesAsSingleRaysDo) {
    InstancedScene scene(78, 2, 40, GetParam());
    int instanceLanes = 0;
    for (int p = 0; p < 600; ++p) {
        Ray rays[8];
        RayPacket8 packet = randomPacket(scene.prims, scene.random(), p, rays);
        HitPacket8 hits;
        scene.bvh.intersect8(packet, hits);
        for (int i = 0; i < 8; ++i) {
            Hit single;
            bool found = (packet.active >> i & 1) && scene.bvh.intersect(packet.ray(i), single);
            EXPECT_EQ(hits.t[i], single.t) << "packet " << p << " lane " << i;
            if (!found) continue;
            EXPECT_EQ(hits.primId[i], single.primId);
            if (scene.prims.isInstance(single.primId)) {
                EXPECT_EQ(hits.subId[i], single.subId);
                ++instanceLanes;
            }
        }
    }
    EXPECT_GT(instanceLanes, 200);
}

TEST_P(BvhKernels, RefittingToTheSamePrimitivesGivesTheBuiltTree) {
    Primitives prims;
    Random r(61);
    addAllKinds(prims, r, 700, 150, 150, 1);
    const Bvh built = build(prims);
    Bvh refitted = build(prims);
    ASSERT_TRUE(refitted.refit(prims, {0, GetParam()}));
    expectSameTree(built, refitted);
    EXPECT_TRUE(refitted.stats().refitted);
    EXPECT_FALSE(built.stats().refitted);
    EXPECT_EQ(refitted.relativeArea(), built.stats().builtArea);
    EXPECT_EQ(refitted.bounds().lo, built.bounds().lo);
    EXPECT_EQ(refitted.bounds().hi, built.bounds().hi);
}

TEST_P(BvhKernels, ARefittedTreeFindsWhatABuiltOneFindsWhereverThePrimitivesWent) {
    // The same counts of every kind, anywhere else: the tree built for the first set, fitted
    // to the second, is slow to search but exact.
    Primitives before, after;
    Random r(62), s(63);
    addAllKinds(before, r, 900, 200, 200, 2);
    addAllKinds(after, s, 900, 200, 200, 2);
    Bvh bvh = build(before);
    ASSERT_TRUE(bvh.refit(after, {0, GetParam()}));
    expectSaneTree(bvh, after);
    EXPECT_GT(bvh.relativeArea(), bvh.stats().builtArea);  // fitted to scattered primitives
    BruteForce oracle;
    oracle.build(after);
    Agreement a;
    for (int i = 0; i < 4000; ++i) compare(after, bvh, oracle, randomRay(after, s, i), a);
    EXPECT_EQ(a.mismatches, 0) << a.first;
    EXPECT_GT(a.hits, a.rays / 4);
    // Packets too.
    for (int p = 0; p < 200; ++p) {
        Ray rays[8];
        RayPacket8 packet = randomPacket(after, s, p, rays);
        HitPacket8 hits;
        bvh.intersect8(packet, hits);
        for (int i = 0; i < 8; ++i) {
            Hit single;
            if ((packet.active >> i & 1) && oracle.intersect(rays[i], single)) {
                EXPECT_EQ(hits.primId[i], single.primId) << "packet " << p << " lane " << i;
            }
        }
    }
}

TEST_P(BvhKernels, ATreeIsNotRefittedToPrimitivesOfOtherCounts) {
    Primitives prims, more, moving;
    Random r(64);
    addAllKinds(prims, r, 100, 20, 20, 1);
    Random r2(64);
    addAllKinds(more, r2, 100, 20, 20, 1);
    more.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, nullptr, 0);
    Random r3(64);
    addAllKinds(moving, r3, 100, 20, 20, 1);
    moving.setMotion(100,
                     MotionPath({Transform(), *Transform::fromMatrix(Mat4::translate(1, 0, 0))}));
    Bvh bvh = build(prims);
    const Bvh built = build(prims);
    EXPECT_FALSE(bvh.refit(more, {0, GetParam()}));
    EXPECT_FALSE(bvh.refit(moving, {0, GetParam()}));   // a sphere that moves is not in the tree
    expectSameTree(bvh, built);                         // unchanged
    EXPECT_FALSE(Bvh().refit(prims, {0, GetParam()}));  // never built
}

TEST(Bvh, InstancesNeedTheirMeshesBvhs) {
    Primitives mesh, prims;
    mesh.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, nullptr, 0);
    prims.addInstance(prims.addSharedMesh(mesh), Transform());
    Bvh bvh;
    EXPECT_THROW(bvh.build(prims), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Kernels, BvhKernels, testing::ValuesIn(kernelSets()),
                         [](const auto& p) { return std::string(Bvh::name(p.param)); });

}  // namespace
}  // namespace glint
